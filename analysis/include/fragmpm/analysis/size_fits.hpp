#pragma once
// Maximum-likelihood fits of fragment-size distributions with confidence intervals
// (docs/design.md "Pooled statistics"):
//
//   Rosin-Rammler / Weibull   P(d) = 1 − exp(−(d/d₀)ⁿ) [RR33], every sample, range [min, max];
//   power law                 N(>d) ∝ d^(−D) for d ≥ d_min (pdf D d_min^D d^(−D−1)), with d_min
//                             chosen by the Kolmogorov-Smirnov criterion of Clauset, Shalizi and
//                             Newman [CSN09]; optionally truncated above at d_max.
//
// Sizes in any positive unit; the fitted d₀ and d_min are in the same unit.
#include <cstddef>
#include <limits>
#include <span>

namespace fragmpm::analysis {

/// A 95 % (or `level`) interval [low, high] around an estimate.
struct Interval {
  double low = 0.0, high = 0.0;
};

struct RosinRammlerFit {
  double d0 = 0.0;       ///< scale d₀ (63.2 % passing)
  double n = 0.0;        ///< uniformity exponent n
  Interval d0_ci, n_ci;  ///< Wald intervals from the observed information
  double d_low = 0.0;    ///< fitted range: smallest and largest sample
  double d_high = 0.0;
  std::size_t samples = 0;
  double ks = 0.0;  ///< Kolmogorov-Smirnov distance of the fit to the samples
};

/// MLE of the two-parameter Weibull ([Wei51]; Rosin-Rammler in comminution): n solves
/// 1/n + mean(ln d) − Σ dⁿ ln d / Σ dⁿ = 0 (Newton with bisection safeguard), d₀ⁿ = mean(dⁿ).
/// Intervals: estimate ± z √(J⁻¹)ᵢᵢ with J the observed information. Throws std::invalid_argument
/// for fewer than 3 samples, non-positive or non-finite values, or all samples equal.
RosinRammlerFit fit_rosin_rammler(std::span<const double> d, double level = 0.95);

struct PowerLawFit {
  double exponent = 0.0;  ///< D of N(>d) ∝ d^(−D)  (CSN's α − 1)
  Interval exponent_ci;
  double d_min = 0.0;                                      ///< lower end of the fitted range
  double d_max = std::numeric_limits<double>::infinity();  ///< upper truncation (∞ = none)
  double d_high = 0.0;                                     ///< largest sample in the fitted range
  std::size_t tail = 0;                                    ///< samples with d ≥ d_min
  std::size_t samples = 0;
  double ks = 0.0;  ///< KS distance of the fit over the tail
};

/// MLE of D above a given d_min. Without truncation D̂ = n / Σ ln(dᵢ/d_min) [CSN09 eq. (3.1), α̂ −
/// 1], and 2 D Σ ln(dᵢ/d_min) is χ² with 2n degrees of freedom, which gives an exact interval.
/// With a finite d_max the likelihood of the truncated law is maximised in D (bisection on the
/// score) and the interval is Wald's from the observed information. Throws std::invalid_argument
/// when fewer than 2 samples lie in [d_min, d_max] or d_min is not positive.
PowerLawFit fit_power_law(std::span<const double> d, double d_min,
                          double d_max = std::numeric_limits<double>::infinity(),
                          double level = 0.95);

/// CSN09 §3.3: every distinct sample with at least `min_tail` samples at or above it is a candidate
/// d_min; the one whose fit has the smallest KS distance over its tail is chosen.
PowerLawFit fit_power_law_csn(std::span<const double> d, std::size_t min_tail = 25,
                              double level = 0.95);

/// Standard normal quantile (Acklam's rational approximation refined by one Halley step).
double normal_quantile(double p);
/// χ² quantile with k degrees of freedom (Wilson-Hilferty; relative error below 1e-3 for k ≥ 10).
double chi_squared_quantile(double p, double k);

}  // namespace fragmpm::analysis
