// SI prefixes (see si_format.hpp).
#include "fragmpm/analysis/si_format.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

namespace fragmpm::analysis {

namespace {

const char* const prefixes[] = {"p", "n", "\u00b5", "m", "", "k", "M", "G"};

/// Index into `prefixes` of the power of 1000 that brings |v| into [1, 1000).
int prefix_index(double v) {
  return std::clamp(static_cast<int>(std::floor(std::log10(std::abs(v)) / 3.0 + 1e-9)), -4, 3) + 4;
}

}  // namespace

SiPrefix si_prefix(double magnitude) {
  if (!(magnitude > 0.0) || !std::isfinite(magnitude)) return SiPrefix{"", 1.0};
  const int i = prefix_index(magnitude);
  return SiPrefix{prefixes[i], std::pow(10.0, -3 * (i - 4))};
}

std::string format_si(double value, const std::string& unit, int significant) {
  if (value == 0.0 || !std::isfinite(value)) return fmt::format("{} {}", value, unit);
  const int digits = std::max(1, significant);
  // Round to the requested digits first: 999.7 must become "1 k", not "1000".
  const int e10 = static_cast<int>(std::floor(std::log10(std::abs(value))));
  const double unit_digit = std::pow(10.0, e10 - digits + 1);
  const double rounded = std::round(value / unit_digit) * unit_digit;
  const int i = prefix_index(rounded);
  const double mantissa = rounded / std::pow(10.0, 3 * (i - 4));
  const int int_digits = static_cast<int>(std::floor(std::log10(std::abs(mantissa)) + 1e-9)) + 1;
  std::string number = fmt::format("{:.{}f}", mantissa, std::max(0, digits - int_digits));
  if (number.find('.') != std::string::npos) {
    number.erase(number.find_last_not_of('0') + 1);
    if (number.back() == '.') number.pop_back();
  }
  return fmt::format("{} {}{}", number, prefixes[i], unit);
}

}  // namespace fragmpm::analysis
