#pragma once
// Pooled CDFs over the members of a study with pointwise bootstrap bands that resample members,
// not fragments (docs/design.md "Pooled statistics"): fragments of one run are correlated (one
// Weibull realisation, one crack pattern), so the run is the independent unit.
#include <cstdint>
#include <span>
#include <vector>

namespace fragmpm::analysis {

/// One member's samples: value (e.g. equivalent diameter) and weight (mass) per fragment.
struct MemberSample {
  std::vector<double> value;
  std::vector<double> mass;
};

/// Pooled number- and mass-weighted CDFs at the points x, with their pointwise bands.
struct CdfBand {
  std::vector<double> x;
  std::vector<double> number, number_low, number_high;
  std::vector<double> mass, mass_low, mass_high;
  int replicates = 0;
  std::uint64_t seed = 0;
};

/// F_N(x) = Σ_m #{v ≤ x} / Σ_m n_m and F_M(x) = Σ_m mass{v ≤ x} / Σ_m mass_m over all members,
/// and the (1 − level)/2 and (1 + level)/2 percentiles of the same pooled CDFs over `replicates`
/// resamplings of the members with replacement (std::mt19937_64 seeded with `seed`; the same seed
/// gives the same bands). Throws std::invalid_argument when no member has samples.
CdfBand bootstrap_cdf_band(std::span<const MemberSample> members, std::span<const double> x,
                           int replicates, std::uint64_t seed, double level = 0.95);

/// `count` points spaced evenly in log between lo and hi (both > 0), or linearly when `log` is
/// false.
std::vector<double> spaced_points(double lo, double hi, int count, bool log);

}  // namespace fragmpm::analysis
