#pragma once
// Empirical cumulative distributions, number- and mass-weighted (docs/design.md; as [XLS21] Fig.
// 17-18).
#include <span>
#include <vector>

namespace fragmpm::analysis {

/// Step CDF of n samples sorted ascending (ties in input order):
///   number_fraction[k] = (k + 1)/n,   mass_fraction[k] = Σ_{j ≤ k} w_j / Σ_j w_j.
/// Both are non-decreasing and end at exactly 1. Empty input gives empty arrays.
struct EmpiricalCdf {
  std::vector<double> value;
  std::vector<double> number_fraction;
  std::vector<double> mass_fraction;
};

/// Throws std::invalid_argument when the sizes differ, a value or weight is not finite, a weight is
/// negative, or the weights sum to zero.
EmpiricalCdf empirical_cdf(std::span<const double> values, std::span<const double> weights);

}  // namespace fragmpm::analysis
