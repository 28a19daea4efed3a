// Grading curves, D_x, and breakage indices on hand-computed curves.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "fragmpm/analysis/grading.hpp"

using namespace fragmpm::analysis;

TEST(Grading, PercentPassingAndCharacteristicSizes) {
  // Four pieces: 1 mm (mass 1), 2 mm (1), 4 mm (2), 8 mm (4); passing 1/8, 1/4, 1/2, 1.
  const std::vector<double> d{8e-3, 1e-3, 4e-3, 2e-3}, m{4, 1, 2, 1};
  const GradingCurve c = grading_curve(d, m);
  ASSERT_EQ(c.d.size(), 4u);
  EXPECT_DOUBLE_EQ(c.passing[0], 0.125);
  EXPECT_DOUBLE_EQ(c.passing[2], 0.5);
  EXPECT_DOUBLE_EQ(c.passing[3], 1.0);
  const GradingSummary s = summarise(c);
  // D10 lies below the first point's 12.5 %: the smallest size. D50 = 4 mm exactly.
  EXPECT_DOUBLE_EQ(s.d10, 1e-3);
  EXPECT_NEAR(s.d50, 4e-3, 1e-15);
  // D60: between (4 mm, 0.5) and (8 mm, 1), log-linear: 4 × 2^(0.1/0.5) mm = 4.595 mm.
  EXPECT_NEAR(s.d60, 4e-3 * std::pow(2.0, 0.2), 1e-12);
  // D90: 4 × 2^(0.4/0.5) = 6.964 mm; C_u = D60 / D10 = 4.595.
  EXPECT_NEAR(s.d90, 4e-3 * std::pow(2.0, 0.8), 1e-12);
  EXPECT_NEAR(s.uniformity, 4.0 * std::pow(2.0, 0.2), 1e-9);
  // Between points the curve is linear in log d: P(2.83 mm) = 0.25 + 0.5 × 0.25.
  EXPECT_NEAR(c.at(2e-3 * std::sqrt(2.0)), 0.375, 1e-12);
  EXPECT_EQ(c.at(0.5e-3), 0.0);
  EXPECT_EQ(c.at(9e-3), 1.0);
}

TEST(Grading, HardinAndLadeOnHandComputedCurves) {
  // Initial: one size, 1 mm. Lower limit 0.1 mm: B_p = ∫ (1 − P₀) over one decade = 1.
  const GradingCurve initial = grading_curve(std::vector<double>{1e-3}, std::vector<double>{1.0});
  // Current: half the mass at 0.1 mm, half at 1 mm. P = 0.5 + 0.5 log₁₀(d / 0.1 mm) in between,
  // so B_t = ∫ P d(log d) = 0.75 and B_r = 0.75.
  const GradingCurve current =
      grading_curve(std::vector<double>{1e-4, 1e-3}, std::vector<double>{1.0, 1.0});
  EXPECT_NEAR(hardin_relative_breakage(initial, current, 1e-4), 0.75, 1e-3);
  // D10 went from 1 mm to 0.1 mm: B10 = 1 − 0.1 / 1 = 0.9.
  EXPECT_NEAR(lade_b10(initial, current), 0.9, 1e-12);
  // No breakage: both zero.
  EXPECT_NEAR(hardin_relative_breakage(initial, initial, 1e-4), 0.0, 1e-12);
  EXPECT_NEAR(lade_b10(initial, initial), 0.0, 1e-12);
  // Everything crushed to the lower limit: B_r = 1.
  const GradingCurve crushed = grading_curve(std::vector<double>{1e-4}, std::vector<double>{1.0});
  EXPECT_NEAR(hardin_relative_breakage(initial, crushed, 1e-4), 1.0, 1e-3);
}

TEST(Grading, HardinWithAGradedInitialCurve) {
  // Initial 1 and 10 mm in equal masses, lower limit 1 mm: 1 − P₀ = 0.5 − 0.5 log₁₀(d/1 mm) on
  // [1, 10] mm → B_p = 0.25 decades... the jump at 1 mm makes P₀ = 0.5 there, so B_p = 0.25.
  const GradingCurve initial =
      grading_curve(std::vector<double>{1e-3, 1e-2}, std::vector<double>{1.0, 1.0});
  // Current: all at 1 mm → P = 1 on [1, 10] mm → B_t = ∫ (1 − P₀) = 0.25, B_r = 1.
  const GradingCurve current = grading_curve(std::vector<double>{1e-3}, std::vector<double>{2.0});
  EXPECT_NEAR(hardin_relative_breakage(initial, current, 1e-3), 1.0, 1e-3);
  // Current: 1 mm (1), 3.162 mm (1): P = 0.5 + 0.5 · 2 log₁₀(d/1 mm) up to 3.162 mm, then 1.
  // ∫ P₀ = 0.75 over the decade; ∫ P = 0.5·0.5 + 0.5·0.5·0.5·... computed: first half decade
  // 0.5 × (0.5 + 1)/2 = 0.375, second half 0.5 → 0.875; B_t = 0.875 − 0.75 = 0.125, B_r = 0.5.
  const GradingCurve half = grading_curve(std::vector<double>{1e-3, 1e-3 * std::sqrt(10.0)},
                                          std::vector<double>{1.0, 1.0});
  EXPECT_NEAR(hardin_relative_breakage(initial, half, 1e-3), 0.5, 1e-3);
}
