// V5 Hertz line contact (docs/verification.md, `hertz`; [XLS21] §4.1, eq. (88)-(89)): the closed
// form, the body-fitted particles of the half cylinder, and the coarsest level relaxed against it.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../../pipeline/src/verify/hertz_particles.hpp"
#include "fragmpm/pipeline/verify_hertz.hpp"

using namespace fragmpm::pipeline;

TEST(VerifyHertz, OracleIsHertzForACylinderOnARigidFlat) {
  const HertzOracle oracle = hertz_oracle();  // E and ν of scenes/verify/hertz.toml
  EXPECT_NEAR(oracle.youngs_modulus, 10e9, 1e-6 * 10e9);
  EXPECT_NEAR(oracle.poisson_ratio, 0.0, 1e-12);
  // Johnson's a² = 4 F R / (π E*), E* = E / (1 − ν²), for R = 4 mm, F = 156.7 N/mm.
  const double b = 2.0 * std::sqrt(oracle.load * oracle.radius / (std::numbers::pi * 10e9));
  EXPECT_NEAR(oracle.half_width(), b, 1e-12 * b);
  EXPECT_NEAR(oracle.half_width(), 0.2825e-3, 0.0005e-3);
  EXPECT_NEAR(oracle.peak_pressure(), 353.1e6, 0.1e6);
  // The elliptic profile carries the load: ∫ p dx = π p_max b / 2 = F (midpoint rule).
  const int n = 200000;
  double integral = 0.0;
  for (int k = 0; k < n; ++k) {
    const double x = -oracle.half_width() + (k + 0.5) * 2.0 * oracle.half_width() / n;
    integral += oracle.pressure(x) * 2.0 * oracle.half_width() / n;
  }
  EXPECT_NEAR(integral, oracle.load, 1e-6 * oracle.load);
  EXPECT_EQ(oracle.pressure(1.01 * oracle.half_width()), 0.0);
}

TEST(VerifyHertz, BodyFittedParticlesFillTheHalfDisk) {
  const double radius = 4e-3, spacing = 0.1e-3;
  const CylinderParticles c = half_cylinder_particles(radius, spacing, 1000.0);
  double area = 0.0;
  for (double v : c.particles.volume0) area += v;
  // The fitted columns follow the chords; the lattice columns near the rim are a staircase.
  EXPECT_NEAR(area, std::numbers::pi * radius * radius / 2.0, 2e-3 * area);
  EXPECT_EQ(c.top.size(), 80u);  // 2R / s columns, each loaded over s: the load is 2R × t
  // The lowest particle of each fitted column has both bottom corners on the circle.
  for (std::size_t p = 0; p < c.particles.size(); ++p) {
    const auto& x = c.particles.x[p];
    if (std::abs(x.x()) > radius / 2.0) continue;
    const auto& r = c.particles.domain[p];
    for (double side : {-0.5, 0.5}) {
      const Vec2 corner = x + side * r.col(0) - 0.5 * r.col(1);
      const double gap =
          corner.y() - (radius - std::sqrt(radius * radius - corner.x() * corner.x()));
      if (std::abs(gap) < 1e-9) continue;  // on the circle
      EXPECT_GT(gap, spacing / 2.0) << "particle " << p << " is neither lowest nor inside";
    }
  }
}

TEST(VerifyHertz, CoarseLevelRelaxesToTheHertzContact) {
  const HertzOracle oracle = hertz_oracle();
  const HertzLevel level = run_hertz_level(0.2e-3);
  EXPECT_TRUE(level.converged);
  EXPECT_NEAR(level.reaction, oracle.load, 1e-3 * oracle.load);
  // Measured at h = 0.2 mm (b / h = 1.4, three loaded nodes): b 1.8 % short, RMS error 7.6 % of
  // p_max, peak nodal pressure 4.7 % low (docs/verification.md).
  EXPECT_NEAR(level.half_width, oracle.half_width(), 0.04 * oracle.half_width());
  EXPECT_LT(level.rms_error, 0.10);
  EXPECT_NEAR(level.peak_pressure, oracle.peak_pressure(), 0.08 * oracle.peak_pressure());
  ASSERT_FALSE(level.profile.empty());
  EXPECT_NEAR(level.profile.front().x, -level.profile.back().x, 1e-12);
}
