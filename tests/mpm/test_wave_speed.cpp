// The wave speed of the step limit (wave_speed.hpp): the Kirchhoff longitudinal tangent over the
// reference density, checked against finite-difference derivatives of the elastic laws' Kirchhoff
// stresses, and independent of the volume change for the Hencky energy.
#include <gtest/gtest.h>

#include <cmath>

#include "fragmpm/mpm/phase_field.hpp"
#include "fragmpm/mpm/wave_speed.hpp"

using namespace fragmpm::mpm;

namespace {
const NeoHookean moduli{158.333e9, 73.077e9};  // Pa: the Brazilian disk's K and G
const double reference_density = 2300.0;       // kg/m³
const double small_strain_modulus = moduli.bulk_modulus + 4.0 * moduli.shear_modulus / 3.0;

/// ∂τ_ii/∂ln λ_i of the neo-Hookean at a diagonal F, by central differences in ln λ_i.
template <int D>
double neo_hookean_tangent(Mat<D> F, int i) {
  const double step = 1e-6;
  Mat<D> up = F, down = F;
  up(i, i) *= std::exp(step);
  down(i, i) *= std::exp(-step);
  return (moduli.kirchhoff<D>(up)(i, i) - moduli.kirchhoff<D>(down)(i, i)) / (2.0 * step);
}

/// ρ₀ c² without the initial-stress term (zero stress passed).
template <int D>
double tangent_from_speed(ElasticLaw law, const Mat<D>& F) {
  const double c = longitudinal_wave_speed<D>(moduli, law, F, Mat<D>::Zero(), reference_density);
  return reference_density * c * c;
}
}  // namespace

TEST(WaveSpeed, SmallStrainSpeedAtTheUndeformedState) {
  for (ElasticLaw law : {ElasticLaw::neo_hookean, ElasticLaw::hencky}) {
    const double c = longitudinal_wave_speed<2>(moduli, law, Mat<2>::Identity(), Mat<2>::Zero(),
                                                reference_density);
    EXPECT_NEAR(c, std::sqrt(small_strain_modulus / reference_density), 1e-9 * c);  // 10.5 km/s
  }
}

TEST(WaveSpeed, NeoHookeanTangentIsTheLargestKirchhoffDerivative) {
  const Mat<2> stretched = Vec<2>(1.4, 0.9).asDiagonal();
  const Mat<2> compressed = Vec<2>(0.7, 1.0).asDiagonal();
  for (const Mat<2>& F : {stretched, compressed}) {
    const double largest = std::max(neo_hookean_tangent<2>(F, 0), neo_hookean_tangent<2>(F, 1));
    EXPECT_NEAR(tangent_from_speed<2>(ElasticLaw::neo_hookean, F), largest, 1e-6 * largest);
  }
  const Mat<3> F3 = Vec<3>(1.3, 0.9, 1.1).asDiagonal();
  double largest = 0.0;
  for (int i = 0; i < 3; ++i) largest = std::max(largest, neo_hookean_tangent<3>(F3, i));
  EXPECT_NEAR(tangent_from_speed<3>(ElasticLaw::neo_hookean, F3), largest, 1e-6 * largest);
  // Stretching stiffens the neo-Hookean: at λ = (1.4, 0.9) the tangent is K + G J^(-2/3)
  // ((2/3) 1.96 + (2/9) 3.77) = 292.7 GPa, 14.4 % above K + 4G/3 = 255.8 GPa.
  EXPECT_NEAR(tangent_from_speed<2>(ElasticLaw::neo_hookean, stretched) / small_strain_modulus,
              1.1443, 0.0005);
}

TEST(WaveSpeed, HenckyTangentDoesNotChangeWithVolume) {
  // τ of the Hencky energy (the sum of its split) is linear in the log strain: its derivative
  // along a stretched direction is λ + 2G = K + 4G/3 however far the particle has opened.
  const double lambda = moduli.bulk_modulus - 2.0 * moduli.shear_modulus / 3.0;
  const double step = 1e-6;
  for (double log_stretch : {-0.2, 0.5, 3.1}) {  // 3.1: the J = 22 of a failed particle
    auto tau_xx = [&](double a) {
      const Mat<2> F = Vec<2>(std::exp(a), 1.0).asDiagonal();
      const TensileSplit<2> split = hencky_tensile_split<2>(lambda, moduli.shear_modulus, F);
      return F.determinant() * (split.tensile_stress + split.compressive_stress)(0, 0);
    };
    const double derivative =
        (tau_xx(log_stretch + step) - tau_xx(log_stretch - step)) / (2.0 * step);
    EXPECT_NEAR(derivative, small_strain_modulus, 1e-5 * small_strain_modulus);
    const Mat<2> F = Vec<2>(std::exp(log_stretch), 1.0).asDiagonal();
    EXPECT_NEAR(tangent_from_speed<2>(ElasticLaw::hencky, F), small_strain_modulus,
                1e-12 * small_strain_modulus);
  }
  // The Cauchy modulus over the current density would give √22 = 4.7 times this speed at J = 22.
  const Mat<2> opened = Vec<2>(22.0, 1.0).asDiagonal();
  EXPECT_NEAR(longitudinal_wave_speed<2>(moduli, ElasticLaw::hencky, opened, Mat<2>::Zero(),
                                         reference_density) /
                  moduli.wave_speed(reference_density / 22.0),
              1.0 / std::sqrt(22.0), 1e-12);
}

TEST(WaveSpeed, AFailedParticleKeepsOnlyTheShearItsSplitKeeps) {
  // Stretched eightfold: the intact neo-Hookean tangent is dominated by G J^(-2/3) (2/3) λ²; a
  // failed particle of the volumetric-deviatoric split keeps no shear energy, so only K remains,
  // while the tensile spectral split keeps its compressive principal stresses and the whole
  // tangent.
  const Mat<2> F = Vec<2>(8.0, 0.9).asDiagonal();
  const double intact = tangent_from_speed<2>(ElasticLaw::neo_hookean, F);
  EXPECT_NEAR(intact / small_strain_modulus, 5.01, 0.01);  // 1,281 GPa against 255.8 GPa
  auto failed = [&](Degradation degradation) {
    const double c =
        longitudinal_wave_speed<2>(moduli, ElasticLaw::neo_hookean, F, Mat<2>::Zero(),
                                   reference_density, kept_shear_fraction(degradation, 1.0));
    return reference_density * c * c;
  };
  EXPECT_NEAR(failed(Degradation::volumetric_deviatoric), moduli.bulk_modulus,
              1e-9 * moduli.bulk_modulus);
  EXPECT_NEAR(failed(Degradation::tensile_spectral), intact, 1e-9 * intact);
  EXPECT_DOUBLE_EQ(kept_shear_fraction(Degradation::isotropic, 0.25), 0.75);
}

TEST(WaveSpeed, CompressionAddsItsInitialStress) {
  // A particle at J = 0.9 under a 5 GPa pressure: c² = (K + 4G/3 + J ‖σ‖) / ρ₀.
  const Mat<2> F = Vec<2>(0.9, 1.0).asDiagonal();
  const Mat<2> stress = -5e9 * Mat<2>::Identity();
  const double c =
      longitudinal_wave_speed<2>(moduli, ElasticLaw::hencky, F, stress, reference_density);
  EXPECT_NEAR(reference_density * c * c, small_strain_modulus + 0.9 * 5e9 * std::sqrt(2.0),
              1e-9 * small_strain_modulus);
}
