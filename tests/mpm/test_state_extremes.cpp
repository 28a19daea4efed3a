// The end-of-run extremes on a constructed state whose volume ratios and principal stresses are
// known in closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "fragmpm/mpm/state_extremes.hpp"

using namespace fragmpm;
using mpm::Mat;

TEST(StateExtremes, LargestVolumeRatioSwollenCountAndLargestPrincipalStress) {
  mpm::Particles<2> P;
  P.resize(4);
  // J = det F: 2.5 (stretch), 3 (stretch and shear), 1, 0.25 (compressed).
  P.F[0] << 2.5, 0.0, 0.0, 1.0;
  P.F[1] << 1.0, 0.5, 0.0, 3.0;
  P.F[2] = Mat<2>::Identity();
  P.F[3] << 0.5, 0.0, 0.0, 0.5;
  // Principal stresses: 100 and −300 MPa; ±250 MPa (pure shear τ = 250 MPa);
  // ±√(50² + 30²) = ±58.31 MPa; 0.
  P.stress[0] << 100e6, 0.0, 0.0, -300e6;
  P.stress[1] << 0.0, 250e6, 250e6, 0.0;
  P.stress[2] << 50e6, 30e6, 30e6, -50e6;
  const mpm::StateExtremes e = mpm::state_extremes<2>(P);
  EXPECT_DOUBLE_EQ(e.largest_J, 3.0);
  EXPECT_EQ(e.largest_J_particle, 1);
  EXPECT_EQ(e.swollen, 2u);  // J = 2.5 and 3 exceed 2
  EXPECT_NEAR(e.largest_stress, 300e6, 1e-6);
  EXPECT_EQ(e.largest_stress_particle, 0);

  // A rotated uniaxial tension σ = R diag(400 MPa, 0) Rᵀ is found through its principal value.
  const double a = 0.3;
  Mat<2> R;
  R << std::cos(a), -std::sin(a), std::sin(a), std::cos(a);
  Mat<2> uniaxial = Mat<2>::Zero();
  uniaxial(0, 0) = 400e6;
  P.stress[3] = R * uniaxial * R.transpose();
  const mpm::StateExtremes f = mpm::state_extremes<2>(P);
  EXPECT_NEAR(f.largest_stress, 400e6, 1e-6);
  EXPECT_EQ(f.largest_stress_particle, 3);
}

TEST(StateExtremes, DescribeNamesTheValuesAndParticles) {
  mpm::Particles<2> P;
  P.resize(2);
  P.F[1] << 2.5, 0.0, 0.0, 1.0;
  P.stress[0] << -345e6, 0.0, 0.0, 10e6;
  EXPECT_EQ(mpm::describe(mpm::state_extremes<2>(P)),
            "largest J = det F 2.5 (particle 1), 1 particle with J > 2, largest |principal "
            "stress| 345 MPa (particle 0)");
}

TEST(StateExtremes, EmptyStateHasNoParticle) {
  const mpm::StateExtremes e = mpm::state_extremes<2>(mpm::Particles<2>{});
  EXPECT_EQ(e.largest_J_particle, -1);
  EXPECT_EQ(e.largest_stress_particle, -1);
  EXPECT_EQ(e.swollen, 0u);
}
