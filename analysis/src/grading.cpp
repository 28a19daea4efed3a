// Grading curves and breakage indices (grading.hpp).
#include "fragmpm/analysis/grading.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace fragmpm::analysis {

double GradingCurve::at(double size) const {
  if (d.empty() || size < d.front()) return 0.0;
  if (size >= d.back()) return 1.0;
  const auto it = std::upper_bound(d.begin(), d.end(), size);
  const std::size_t k = static_cast<std::size_t>(it - d.begin());  // d[k-1] ≤ size < d[k]
  const double t = std::log(size / d[k - 1]) / std::log(d[k] / d[k - 1]);
  return passing[k - 1] + t * (passing[k] - passing[k - 1]);
}

double GradingCurve::size_passing(double fraction) const {
  if (d.empty()) return 0.0;
  if (fraction <= passing.front()) return d.front();
  for (std::size_t k = 1; k < d.size(); ++k)
    if (passing[k] >= fraction) {
      const double t = (fraction - passing[k - 1]) / (passing[k] - passing[k - 1]);
      return d[k - 1] * std::pow(d[k] / d[k - 1], t);
    }
  return d.back();
}

GradingCurve grading_curve(std::span<const double> size, std::span<const double> mass) {
  if (size.size() != mass.size())
    throw std::invalid_argument("grading_curve: sizes and masses differ in length");
  std::vector<std::size_t> order(size.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return size[a] < size[b]; });
  double total = 0.0;
  for (double m : mass) total += m;
  if (!(total > 0.0)) throw std::invalid_argument("grading_curve: zero total mass");
  GradingCurve c;
  double cumulative = 0.0;
  for (std::size_t i : order) {
    if (!(size[i] > 0.0)) throw std::invalid_argument("grading_curve: sizes must be positive");
    cumulative += mass[i];
    if (!c.d.empty() && c.d.back() == size[i])
      c.passing.back() = cumulative / total;
    else {
      c.d.push_back(size[i]);
      c.passing.push_back(cumulative / total);
    }
  }
  c.passing.back() = 1.0;
  return c;
}

GradingSummary summarise(const GradingCurve& c) {
  GradingSummary s;
  s.d10 = c.size_passing(0.10);
  s.d30 = c.size_passing(0.30);
  s.d50 = c.size_passing(0.50);
  s.d60 = c.size_passing(0.60);
  s.d90 = c.size_passing(0.90);
  s.uniformity = s.d60 / s.d10;
  s.curvature = s.d30 * s.d30 / (s.d10 * s.d60);
  return s;
}

double hardin_relative_breakage(const GradingCurve& initial, const GradingCurve& current,
                                double d_lower, int points) {
  if (initial.d.empty() || current.d.empty())
    throw std::invalid_argument("hardin_relative_breakage: empty grading curve");
  const double d_upper = initial.d.back();
  if (!(d_lower > 0.0 && d_lower < d_upper))
    throw std::invalid_argument("hardin_relative_breakage: d_lower must lie in (0, largest size)");
  // Midpoint rule in u = log₁₀ d: the curves are piecewise linear in u with jumps, so the error
  // falls as 1/points.
  const double u0 = std::log10(d_lower), u1 = std::log10(d_upper);
  const double du = (u1 - u0) / points;
  double potential = 0.0, total = 0.0;
  for (int i = 0; i < points; ++i) {
    const double d = std::pow(10.0, u0 + (i + 0.5) * du);
    const double p0 = initial.at(d);
    potential += (1.0 - p0) * du;
    total += (current.at(d) - p0) * du;
  }
  return total / potential;
}

double lade_b10(const GradingCurve& initial, const GradingCurve& current) {
  return 1.0 - current.size_passing(0.10) / initial.size_passing(0.10);
}

}  // namespace fragmpm::analysis
