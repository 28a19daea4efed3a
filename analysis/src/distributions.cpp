#include "fragmpm/analysis/distributions.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>

namespace fragmpm::analysis {

EmpiricalCdf empirical_cdf(std::span<const double> values, std::span<const double> weights) {
  if (values.size() != weights.size())
    throw std::invalid_argument("empirical_cdf: " + std::to_string(values.size()) + " values but " +
                                std::to_string(weights.size()) + " weights");
  const std::size_t n = values.size();
  EmpiricalCdf cdf;
  if (n == 0) return cdf;
  double total = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    if (!std::isfinite(values[k]))
      throw std::invalid_argument("empirical_cdf: value " + std::to_string(k) + " is not finite");
    if (!std::isfinite(weights[k]) || weights[k] < 0.0)
      throw std::invalid_argument("empirical_cdf: weight " + std::to_string(k) + " = " +
                                  std::to_string(weights[k]) +
                                  "; expected a finite, non-negative mass");
    total += weights[k];
  }
  if (!(total > 0.0)) throw std::invalid_argument("empirical_cdf: the weights sum to zero");
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return values[a] < values[b]; });
  cdf.value.resize(n);
  cdf.number_fraction.resize(n);
  cdf.mass_fraction.resize(n);
  double running = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    cdf.value[k] = values[order[k]];
    cdf.number_fraction[k] = static_cast<double>(k + 1) / static_cast<double>(n);
    running += weights[order[k]];
    cdf.mass_fraction[k] = std::min(1.0, running / total);
  }
  // The last entries are exactly 1 by construction of (k+1)/n; the running sum may round below.
  cdf.mass_fraction.back() = 1.0;
  return cdf;
}

}  // namespace fragmpm::analysis
