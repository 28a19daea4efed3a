// Neo-Hookean ([XLS21] eq. (16)-(17), plane strain): zero stress at F = I, objectivity, and the
// Kirchhoff stress equal to the finite-difference derivative of the energy, τ = (∂ψ/∂F) Fᵀ.
#include <gtest/gtest.h>

#include <cmath>

#include "fragmpm/mpm/neo_hookean.hpp"

using namespace fragmpm::mpm;

namespace {
const NeoHookean model{158.333e9, 73.077e9};
Mat<2> sample_F() {
  Mat<2> F;
  F << 1.08, 0.13, -0.05, 0.93;
  return F;
}
}  // namespace

TEST(NeoHookean, ZeroStressAndEnergyAtIdentity) {
  EXPECT_NEAR(model.cauchy<2>(Mat<2>::Identity()).norm(), 0.0, 1e-6);  // Pa, against ~1e11 moduli
  EXPECT_NEAR(model.energy_density<2>(Mat<2>::Identity()), 0.0, 1e-6);
  EXPECT_NEAR(model.kirchhoff_out_of_plane(Mat<2>::Identity()), 0.0, 1e-6);
}

TEST(NeoHookean, ObjectiveUnderRotation) {
  const Mat<2> F = sample_F();
  for (double angle : {0.3, 1.7, -2.9}) {
    Mat<2> R;
    R << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
    const Mat<2> rotated = model.cauchy<2>(R * F);
    const Mat<2> expected = R * model.cauchy<2>(F) * R.transpose();
    EXPECT_NEAR((rotated - expected).norm() / expected.norm(), 0.0, 1e-13);
    EXPECT_NEAR(model.energy_density<2>(R * F), model.energy_density<2>(F), 1e-3);
  }
}

TEST(NeoHookean, KirchhoffStressIsTheDerivativeOfTheEnergy) {
  const Mat<2> F = sample_F();
  Mat<2> P = Mat<2>::Zero();  // first Piola–Kirchhoff by central differences
  const double step = 1e-6;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      Mat<2> plus = F, minus = F;
      plus(i, j) += step;
      minus(i, j) -= step;
      P(i, j) = (model.energy_density<2>(plus) - model.energy_density<2>(minus)) / (2 * step);
    }
  const Mat<2> tau = model.kirchhoff<2>(F);
  EXPECT_NEAR((P * F.transpose() - tau).norm() / tau.norm(), 0.0, 1e-7);
}

TEST(NeoHookean, SmallStrainLimitGivesPlaneStrainHooke) {
  // Uniaxial strain ε in x: σ_xx = (K + 4G/3) ε, σ_yy = (K − 2G/3) ε.
  const double eps = 1e-7;
  Mat<2> F = Mat<2>::Identity();
  F(0, 0) += eps;
  const Mat<2> sigma = model.cauchy<2>(F);
  const double K = model.bulk_modulus, G = model.shear_modulus;
  EXPECT_NEAR(sigma(0, 0) / ((K + 4 * G / 3) * eps), 1.0, 1e-6);
  EXPECT_NEAR(sigma(1, 1) / ((K - 2 * G / 3) * eps), 1.0, 1e-6);
}
