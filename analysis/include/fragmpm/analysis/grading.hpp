#pragma once
// Grading curves (percent passing by mass against size) and breakage indices measured against the
// initial grains (docs/design.md "Pooled statistics"): Hardin's relative breakage B_r [Har85] and
// Lade's B10 [LYB96].
#include <span>
#include <vector>

namespace fragmpm::analysis {

/// Passing fraction P (0 … 1, by mass) at the sizes d (ascending, distinct): the fraction of the
/// mass in pieces of size ≤ d. Between points P is linear in log d; below the first size P = 0
/// (the curve jumps to P[0] there, the smallest piece's share), above the last P = 1.
struct GradingCurve {
  std::vector<double> d;
  std::vector<double> passing;
  /// P(size) with the interpolation above.
  double at(double size) const;
  /// D_x: the size at which P reaches `fraction` (log-linear between points; the smallest size
  /// when the first point already passes it).
  double size_passing(double fraction) const;
};

/// The grading curve of pieces with sizes and masses (ties merged). Throws std::invalid_argument
/// for mismatched sizes, non-positive sizes or a zero total mass.
GradingCurve grading_curve(std::span<const double> size, std::span<const double> mass);

struct GradingSummary {
  double d10 = 0, d30 = 0, d50 = 0, d60 = 0, d90 = 0;
  double uniformity = 0;  ///< C_u = D60 / D10
  double curvature = 0;   ///< C_c = D30² / (D10 D60)
};
GradingSummary summarise(const GradingCurve& curve);

/// Hardin's relative breakage B_r = B_t / B_p: with the breakage potential of a size b_p = 1 − P,
/// B_p = ∫ (1 − P₀) d(log₁₀ d) and B_t = ∫ (P − P₀) d(log₁₀ d) over [d_lower, largest initial
/// size], d_lower the size below which pieces count as unbreakable (Hardin: the 0.074 mm sieve;
/// here a parameter, since the grains are micrometres). Integrated on `points` log-spaced sizes.
double hardin_relative_breakage(const GradingCurve& initial, const GradingCurve& current,
                                double d_lower, int points = 4000);

/// Lade, Yamamuro and Bopp's B10 = 1 − D10 / D10,initial.
double lade_b10(const GradingCurve& initial, const GradingCurve& current);

}  // namespace fragmpm::analysis
