// Axis ticks (see axis_ticks.hpp).
#include "fragmpm/analysis/axis_ticks.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fragmpm::analysis {

namespace {

/// Decimal places that show every multiple of `step` exactly (step = 1, 2 or 5 × 10^k).
int decimals_for(double step) {
  return std::max(0, -static_cast<int>(std::floor(std::log10(step) + 1e-9)));
}

std::string fixed(double v, int decimals) {
  std::string s = fmt::format("{:.{}f}", v, decimals);
  if (s.find_first_not_of("-0.") == std::string::npos)
    s = decimals > 0 ? fmt::format("{:.{}f}", 0.0, decimals) : "0";
  return s;
}

RichText power_of_ten(int exponent, const std::string& prefix) {
  return {{prefix + "10", false}, {std::to_string(exponent), true}};
}

}  // namespace

double nice_step(double span, int target) {
  const double raw = span / std::max(target, 1);
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  const double n = raw / magnitude;
  const double m = n < 1.5   ? 1.0
                   : n < 3.0 ? 2.0
                   : n < 7.0 ? 5.0
                             : 10.0;  // nearest on the 1-2-5 ladder
  return m * magnitude;
}

AxisTicks linear_ticks(double lo, double hi, double margin) {
  if (hi < lo) std::swap(lo, hi);
  if (hi == lo) {
    const double half = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= half;
    hi += half;
  } else {
    const double pad = margin * (hi - lo);
    lo -= pad;
    hi += pad;
  }
  AxisTicks t;
  t.lo = lo;
  t.hi = hi;
  const double step = nice_step(hi - lo, 6);
  const double tolerance = 1e-9 * step;
  const long long first = static_cast<long long>(std::ceil((lo - tolerance) / step));
  const long long last = static_cast<long long>(std::floor((hi + tolerance) / step));
  double largest = 0.0;
  for (long long k = first; k <= last; ++k) {
    const double v = static_cast<double>(k) * step;  // k·step, not a running sum: no drift
    t.major.push_back(v);
    largest = std::max(largest, std::abs(v));
  }
  int shift = 0;
  if (largest > 0.0 && (largest >= 1e5 || largest < 1e-2))
    shift = 3 * static_cast<int>(std::floor(std::log10(largest) / 3.0));
  const double scale = std::pow(10.0, -shift);
  const int decimals = decimals_for(step * scale);
  for (double v : t.major) t.labels.push_back({{fixed(v * scale, decimals), false}});
  if (shift != 0) t.multiplier = power_of_ten(shift, "x");
  return t;
}

AxisTicks log_ticks(double lo, double hi, double margin) {
  if (hi < lo) std::swap(lo, hi);
  double a = std::log10(lo), b = std::log10(hi);
  if (b - a < 1e-9) {
    a -= 0.5;
    b += 0.5;
  } else {
    const double pad = margin * (b - a);
    a -= pad;
    b += pad;
  }
  AxisTicks t;
  t.lo = std::pow(10.0, a);
  t.hi = std::pow(10.0, b);
  const int e0 = static_cast<int>(std::floor(a)) - 1, e1 = static_cast<int>(std::ceil(b)) + 1;
  auto inside = [&](double v) {
    const double l = std::log10(v);
    return l >= a - 1e-9 && l <= b + 1e-9;
  };
  std::vector<double> decades, ones_twos_fives, all;
  for (int e = e0; e <= e1; ++e) {
    for (int m = 1; m <= 9; ++m) {
      const double v = m * std::pow(10.0, e);
      if (!inside(v)) continue;
      all.push_back(v);
      if (m == 1) decades.push_back(v);
      if (m == 1 || m == 2 || m == 5) ones_twos_fives.push_back(v);
    }
  }
  if (decades.size() >= 3) {
    const std::size_t every = (decades.size() + 7) / 8;  // at most 8 labelled decades
    const int first_exp = static_cast<int>(std::lround(std::log10(decades.front())));
    for (double v : decades) {
      const int e = static_cast<int>(std::lround(std::log10(v)));
      if ((e - first_exp) % static_cast<int>(every) == 0) t.major.push_back(v);
    }
    if (decades.size() <= 7)
      for (double v : all)
        if (std::find(t.major.begin(), t.major.end(), v) == t.major.end()) t.minor.push_back(v);
  } else if (ones_twos_fives.size() >= 2) {
    t.major = ones_twos_fives;
    for (double v : all)
      if (std::find(t.major.begin(), t.major.end(), v) == t.major.end()) t.minor.push_back(v);
  } else {
    t.major = all;
  }
  if (t.major.empty()) t.major.push_back(std::pow(10.0, 0.5 * (a + b)));  // a sliver of one decade
  const bool plain = std::all_of(t.major.begin(), t.major.end(), [](double v) {
    return v >= 1e-3 * (1 - 1e-9) && v <= 1e4 * (1 + 1e-9);
  });
  for (double v : t.major) {
    const int e = static_cast<int>(std::floor(std::log10(v) + 1e-9));
    const double m = v / std::pow(10.0, e);
    const long long mi = std::llround(m);
    const bool integer_mantissa = std::abs(m - static_cast<double>(mi)) < 1e-6;
    if (plain) {
      const int decimals = std::max(0, -e);
      t.labels.push_back({{fixed(v, integer_mantissa ? decimals : decimals + 2), false}});
    } else if (integer_mantissa && mi == 1) {
      t.labels.push_back(power_of_ten(e, ""));
    } else {
      const std::string mantissa = integer_mantissa ? std::to_string(mi) : fmt::format("{:.2g}", m);
      t.labels.push_back(power_of_ten(e, mantissa + "x"));
    }
  }
  return t;
}

std::string plain_text(const RichText& text) {
  std::string s;
  for (const TextRun& r : text) s += r.superscript ? "^" + r.text : r.text;
  return s;
}

}  // namespace fragmpm::analysis
