// Damage laws against their closed forms: Rankine linear softening ([XLS21] eq. (19)-(21)) along
// uniaxial tension, the fracture energy of one softening element, the snap-back limit, degradation
// of the stress ([HH17] eq. (26)-(27); [XLS21] eq. (7)), time to failure ([HH17] eq. (24)) and
// Weibull strengths ([HH17] eq. (25)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>

#include "fragmpm/mpm/damage_law.hpp"

namespace mpm = fragmpm::mpm;

namespace {

// A glass-like material: E = 70 GPa, ν = 0.22, σ_f = 50 MPa, G_f = 10 J/m².
constexpr double kE = 70e9, kNu = 0.22, kStrength = 50e6, kGf = 10.0;

mpm::NeoHookean glass() {
  return {kE / (3.0 * (1.0 - 2.0 * kNu)), kE / (2.0 * (1.0 + kNu))};
}

mpm::RankineSoftening rankine() {
  return {kGf, kE};
}

/// Uniaxial stress in 3D: F = diag(1 + ε, λ, λ) with λ chosen (Newton) so that the lateral stress
/// of the undamaged material vanishes. Damage does not move the lateral stress off zero (a zero
/// principal stress is neither scaled nor kept differently), so this is also the damaged path.
mpm::Mat<3> uniaxial_F(const mpm::NeoHookean& m, double strain) {
  double lambda = 1.0 - kNu * strain;
  for (int it = 0; it < 50; ++it) {
    auto lateral = [&](double l) {
      mpm::Mat<3> F = mpm::Mat<3>::Identity();
      F(0, 0) = 1.0 + strain;
      F(1, 1) = F(2, 2) = l;
      return m.cauchy<3>(F)(1, 1);
    };
    const double f = lateral(lambda), dl = 1e-7;
    const double df = (lateral(lambda + dl) - lateral(lambda - dl)) / (2.0 * dl);
    const double step = f / df;
    lambda -= step;
    if (std::abs(step) < 1e-15) break;
  }
  mpm::Mat<3> F = mpm::Mat<3>::Identity();
  F(0, 0) = 1.0 + strain;
  F(1, 1) = F(2, 2) = lambda;
  return F;
}

}  // namespace

TEST(DamageLaw, SofteningModulusAndSnapBackLimit) {
  const double Hbar = kStrength * kStrength / (2.0 * kE * kGf);  // [XLS21] eq. (21): 1785.7 1/m
  const double l = 0.4e-3;
  EXPECT_NEAR(mpm::rankine_softening_modulus(kStrength, rankine(), l), Hbar * l / (1.0 - Hbar * l),
              1e-12);

  // Largest characteristic length: H̄ l_ch = 1 → l_ch = 2 E G_f / σ_f² (0.56 mm for this glass).
  const double l_max = mpm::rankine_largest_characteristic_length(kStrength, rankine());
  EXPECT_NEAR(l_max, 2.0 * kE * kGf / (kStrength * kStrength), 1e-15);
  EXPECT_NEAR(l_max, 1.0 / Hbar, 1e-15);
  EXPECT_GT(mpm::rankine_softening_modulus(kStrength, rankine(), 0.999 * l_max), 0.0);
  EXPECT_TRUE(std::isnan(mpm::rankine_softening_modulus(kStrength, rankine(), l_max)));
  EXPECT_TRUE(std::isnan(mpm::rankine_softening_modulus(kStrength, rankine(), 2.0 * l_max)));
}

TEST(DamageLaw, RankineFollowsEquation20AlongUniaxialTensionAndSoftensLinearly) {
  const mpm::NeoHookean m = glass();
  const double l = 0.2e-3 * std::sqrt(3.0);  // cell diagonal of h = 0.2 mm in 3D
  const double Hs = mpm::rankine_softening_modulus(kStrength, rankine(), l);
  const double eps_f = kStrength / kE, eps_u = kStrength * (1.0 + Hs) / (kE * Hs);
  ASSERT_GT(eps_u, 1.5 * eps_f);

  double history = 0.0, damage = 0.0;
  const int n = 400;
  double last_stress = 0.0;
  for (int k = 1; k <= n; ++k) {
    const double eps = 1.2 * eps_u * k / n;
    const mpm::Mat<3> F = uniaxial_F(m, eps);
    const mpm::Mat<3> trial = m.cauchy<3>(F);
    mpm::update_damage<3>(rankine(), trial, kStrength, l, 1e-8, history, damage);
    const double s1 = trial(0, 0);
    // eq. (19-20) in closed form, from the trial stress actually reached.
    const double R = std::max(kStrength, s1);
    const double d_expected = std::min(1.0, (1.0 + Hs) * (1.0 - kStrength / R));
    EXPECT_NEAR(damage, d_expected, 1e-12) << "eps = " << eps;
    EXPECT_NEAR(history, s1, 1e-9 * s1);

    const double stress =
        mpm::degrade_stress<3>(trial, damage, mpm::Degradation::tensile_spectral)(0, 0);
    // Linear elastic up to ε_f, then the straight line from (ε_f, σ_f) to (ε_u, 0); the
    // neo-Hookean's finite-strain curvature at ε ~ 1e-3 is within 0.3 % of σ_f.
    const double linear =
        eps <= eps_f ? kE * eps : std::max(0.0, kStrength * (eps_u - eps) / (eps_u - eps_f));
    EXPECT_NEAR(stress, linear, 3e-3 * kStrength) << "eps = " << eps;
    if (eps > eps_f) {
      EXPECT_LE(stress, last_stress + 1e-9 * kStrength);  // softening branch only falls
    }
    last_stress = stress;
  }
  EXPECT_EQ(damage, 1.0);
  EXPECT_EQ(last_stress, 0.0);
}

TEST(DamageLaw, OneSofteningElementDissipatesFractureEnergyTimesArea) {
  // A bar element of length l_ch (one particle of the crack band) and cross-section A pulled until
  // it fails dissipates G_f A: Σ Δd ψ_t V with V = l_ch A.
  const mpm::NeoHookean m = glass();
  const double area = 2.5e-6;  // m²
  for (const double h : {0.1e-3, 0.2e-3, 0.3e-3}) {
    const double l = h * std::sqrt(3.0);
    const double Hs = mpm::rankine_softening_modulus(kStrength, rankine(), l);
    const double eps_u = kStrength * (1.0 + Hs) / (kE * Hs);
    for (const mpm::Degradation deg :
         {mpm::Degradation::tensile_spectral, mpm::Degradation::isotropic}) {
      double history = 0.0, damage = 0.0, dissipated = 0.0, work = 0.0;
      double prev_eps = 0.0, prev_stress = 0.0;
      const int n = 20000;
      for (int k = 1; k <= n; ++k) {
        const double eps = 1.05 * eps_u * k / n;
        const mpm::Mat<3> F = uniaxial_F(m, eps);
        const double d_old = damage;
        mpm::update_damage<3>(rankine(), m.cauchy<3>(F), kStrength, l, 1e-8, history, damage);
        // ψ_t at the end of the increment: the energy released at fixed strain (first order in
        // 1/n).
        dissipated += (damage - d_old) * mpm::degradable_energy<3>(m, F, deg);
        // Work per reference volume by the trapezoidal rule on the nominal stress P = J σ F⁻ᵀ.
        const mpm::Mat<3> P = F.determinant() *
                              mpm::degrade_stress<3>(m.cauchy<3>(F), damage, deg) *
                              F.inverse().transpose();
        work += 0.5 * (P(0, 0) + prev_stress) * (eps - prev_eps);
        prev_eps = eps;
        prev_stress = P(0, 0);
      }
      ASSERT_EQ(damage, 1.0);
      const double volume = l * area;
      EXPECT_NEAR(dissipated * volume, kGf * area, 0.01 * kGf * area) << "h = " << h;
      // Fully damaged, nothing is stored: all the work went into the crack.
      EXPECT_NEAR(work * volume, kGf * area, 0.01 * kGf * area) << "h = " << h;
      EXPECT_NEAR(dissipated, work, 0.005 * work) << "h = " << h;
    }
  }
}

TEST(DamageLaw, SnapBackParticleFailsAtTheCappedStrengthAndDissipatesFractureEnergy) {
  // A strength whose H̄ l_ch ≥ 1 at this l_ch (e.g. a strong Weibull draw) has no softening branch.
  // Its strength is capped at √(2 E G_f / l_ch) [BO83]: it fails at once when σ̄₁ reaches the cap,
  // far below its own strength, and releases G_f per crack area, not σ_f² / (2E) per volume.
  const double l = 1e-3, strong = 4.0 * kStrength;
  const double cap = std::sqrt(2.0 * kE * kGf / l);  // 26.5 MPa here
  ASSERT_TRUE(std::isnan(mpm::rankine_softening_modulus(strong, rankine(), l)));
  EXPECT_DOUBLE_EQ(mpm::rankine_largest_strength(rankine(), l), cap);
  mpm::Mat<2> s = mpm::Mat<2>::Zero();
  s(0, 0) = 0.99 * cap;
  double history = 0.0, damage = 0.0;
  mpm::update_damage<2>(rankine(), s, strong, l, 1e-8, history, damage);
  EXPECT_EQ(damage, 0.0);
  s(0, 0) = 1.001 * cap;
  mpm::update_damage<2>(rankine(), s, strong, l, 1e-8, history, damage);
  EXPECT_EQ(damage, 1.0);

  // Uniaxial stress to failure: the dissipated energy of the element l_ch × A is G_f A.
  const mpm::NeoHookean m = glass();
  const double area = 2.5e-6;
  double h3 = 0.0, d3 = 0.0, dissipated = 0.0;
  const int n = 20000;
  for (int k = 1; k <= n && d3 < 1.0; ++k) {
    const mpm::Mat<3> F = uniaxial_F(m, 2.0 * cap / kE * k / n);
    const double d_old = d3;
    mpm::update_damage<3>(rankine(), m.cauchy<3>(F), strong, l, 1e-8, h3, d3);
    dissipated +=
        (d3 - d_old) * mpm::degradable_energy<3>(m, F, mpm::Degradation::tensile_spectral);
  }
  ASSERT_EQ(d3, 1.0);
  EXPECT_NEAR(dissipated * l * area, kGf * area, 0.01 * kGf * area);
  // Failing at its own strength would have released 16 × (σ_f / cap)² ≈ 57 times more.
  EXPECT_LT(dissipated, 0.1 * strong * strong / (2.0 * kE));
}

TEST(DamageLaw, DamageNeverHealsAndNoDamageIsInert) {
  const double l = 0.2e-3 * std::sqrt(2.0);
  mpm::Mat<2> s = mpm::Mat<2>::Zero();
  s(1, 1) = 1.2 * kStrength;
  double history = 0.0, damage = 0.0;
  mpm::update_damage<2>(rankine(), s, kStrength, l, 1e-8, history, damage);
  const double d1 = damage;
  EXPECT_GT(d1, 0.0);
  mpm::update_damage<2>(rankine(), mpm::Mat<2>(-s), kStrength, l, 1e-8, history,
                        damage);  // unload to compression
  EXPECT_EQ(damage, d1);
  EXPECT_EQ(history, 1.2 * kStrength);

  double h0 = 0.0, d0 = 0.0;
  mpm::update_damage<2>(mpm::NoDamage{}, s, kStrength, l, 1e-8, h0, d0);
  EXPECT_EQ(h0, 0.0);
  EXPECT_EQ(d0, 0.0);
}

TEST(DamageLaw, LargestPrincipalStressIsTheInPlaneMaximum) {
  // σ = [[1, 2], [2, -2]] MPa: principal values (−1 ± 5)/2 → 2 and −3.
  mpm::Mat<2> s;
  s << 1e6, 2e6, 2e6, -2e6;
  EXPECT_NEAR(mpm::largest_principal_stress<2>(s), 2e6, 1e-6);
  mpm::Mat<3> t = mpm::Mat<3>::Zero();
  t.topLeftCorner<2, 2>() = s;
  t(2, 2) = -5e6;
  EXPECT_NEAR(mpm::largest_principal_stress<3>(t), 2e6, 1e-3);
  t(2, 2) = 7e6;
  EXPECT_NEAR(mpm::largest_principal_stress<3>(t), 7e6, 1e-3);
}

TEST(DamageLaw, SpectralDegradationKeepsCompressionAndRemovesTension) {
  // Principal stresses +30 MPa and −80 MPa on axes rotated by 30°.
  const double c = std::cos(0.5235987755982988), sn = std::sin(0.5235987755982988);
  mpm::Mat<2> Q;
  Q << c, -sn, sn, c;
  const mpm::Mat<2> principal = (mpm::Vec<2>() << 30e6, -80e6).finished().asDiagonal();
  const mpm::Mat<2> sigma = Q * principal * Q.transpose();

  // Fully damaged: the tension is gone, the compression is unchanged.
  const mpm::Mat<2> full = mpm::degrade_stress<2>(sigma, 1.0, mpm::Degradation::tensile_spectral);
  const mpm::Mat<2> compressive_only =
      Q * (mpm::Vec<2>() << 0.0, -80e6).finished().asDiagonal() * Q.transpose();
  EXPECT_LT((full - compressive_only).norm(), 1e-6 * 80e6);
  // Half damaged: the tensile principal value is halved.
  const mpm::Mat<2> half = mpm::degrade_stress<2>(sigma, 0.5, mpm::Degradation::tensile_spectral);
  EXPECT_LT(
      (half - Q * (mpm::Vec<2>() << 15e6, -80e6).finished().asDiagonal() * Q.transpose()).norm(),
      1e-6 * 80e6);
  // Pure compression survives full damage untouched; pure tension vanishes.
  const mpm::Mat<3> pressure = -100e6 * mpm::Mat<3>::Identity();
  EXPECT_LT(
      (mpm::degrade_stress<3>(pressure, 1.0, mpm::Degradation::tensile_spectral) - pressure).norm(),
      1e-6);
  EXPECT_LT(mpm::degrade_stress<3>(mpm::Mat<3>(-pressure), 1.0, mpm::Degradation::tensile_spectral)
                .norm(),
            1e-6);
  // Undamaged: unchanged.
  EXPECT_EQ(mpm::degrade_stress<2>(sigma, 0.0, mpm::Degradation::tensile_spectral), sigma);

  // Isotropic ([XLS21] eq. (7)) scales everything, compression included.
  EXPECT_LT(
      (mpm::degrade_stress<2>(sigma, 0.25, mpm::Degradation::isotropic) - 0.75 * sigma).norm(),
      1e-9);
  EXPECT_LT(mpm::degrade_stress<2>(sigma, 1.0, mpm::Degradation::isotropic).norm(), 1e-9);
}

TEST(DamageLaw, DegradableEnergyIsTheTensileShare) {
  const mpm::NeoHookean m = glass();
  // Pure compression: nothing to degrade spectrally; isotropic degrades all of ψ.
  const mpm::Mat<2> squeeze = 0.999 * mpm::Mat<2>::Identity();
  EXPECT_EQ(mpm::degradable_energy<2>(m, squeeze, mpm::Degradation::tensile_spectral), 0.0);
  EXPECT_DOUBLE_EQ(mpm::degradable_energy<2>(m, squeeze, mpm::Degradation::isotropic),
                   m.energy_density<2>(squeeze));
  // Equibiaxial tension in 3D: everything is tensile, ψ_t = ½ τ : ln V = ψ to O(ε).
  const mpm::Mat<3> stretch = 1.001 * mpm::Mat<3>::Identity();
  const double psi = m.energy_density<3>(stretch);
  EXPECT_NEAR(mpm::degradable_energy<3>(m, stretch, mpm::Degradation::tensile_spectral), psi,
              3e-3 * psi);
  // Uniaxial stress: ψ_t = ½ σ₁ ε₁ = ψ (the lateral stresses vanish).
  const mpm::Mat<3> F = uniaxial_F(m, 1e-3);
  const double psi_u = m.energy_density<3>(F);
  EXPECT_NEAR(mpm::degradable_energy<3>(m, F, mpm::Degradation::tensile_spectral), psi_u,
              3e-3 * psi_u);
  // Plane strain, rotated uniaxial stretch: only the in-plane tensile direction contributes
  // ½ τ₁ ln λ₁ (λ₃ = 1), independent of the rotation.
  const double c = std::cos(0.3), s = std::sin(0.3);
  mpm::Mat<2> Q;
  Q << c, -s, s, c;
  const mpm::Mat<2> U = (mpm::Vec<2>() << 1.002, 1.0).finished().asDiagonal();
  const double tau1 = m.kirchhoff<2>(U)(0, 0);
  ASSERT_GT(tau1, 0.0);
  ASSERT_GT(m.kirchhoff<2>(U)(1, 1),
            0.0);  // lateral Kirchhoff stress of uniaxial strain is tensile too
  const double expected = 0.5 * tau1 * std::log(1.002);  // ln λ₂ = ln λ₃ = 0
  EXPECT_NEAR(mpm::degradable_energy<2>(m, mpm::Mat<2>(Q * U), mpm::Degradation::tensile_spectral),
              expected, 1e-9 * expected);
}

TEST(DamageLaw, TimeToFailureReachesOneAfterExactlyTauOverDtSteps) {
  // τ = l_ch / c_f = 1 mm / 1000 m/s = 1 µs; Δt = 0.1 µs → 10 steps once σ̄₁ ≥ σ_f.
  const mpm::TimeToFailure law{1000.0};
  const double l = 1e-3, dt = 1e-7;
  mpm::Mat<2> s = mpm::Mat<2>::Zero();
  double history = 0.0, damage = 0.0;
  s(0, 0) = 0.999 * kStrength;
  for (int k = 0; k < 5; ++k) mpm::update_damage<2>(law, s, kStrength, l, dt, history, damage);
  EXPECT_EQ(damage, 0.0);  // below the strength nothing starts
  s(0, 0) = kStrength;     // failure starts at σ̄₁ = σ_f
  for (int k = 1; k <= 10; ++k) {
    mpm::update_damage<2>(law, s, kStrength, l, dt, history, damage);
    if (k < 10) {
      EXPECT_NEAR(damage, 0.1 * k, 1e-12);
      EXPECT_LT(damage, 1.0) << "step " << k;
    }
  }
  EXPECT_EQ(damage, 1.0);
  mpm::update_damage<2>(law, s, kStrength, l, dt, history, damage);
  EXPECT_EQ(damage, 1.0);

  // A step size that does not divide τ: ceil(τ/Δt) steps.
  double h2 = 0.0, d2 = 0.0;
  s(0, 0) = 2.0 * kStrength;
  int steps = 0;
  while (d2 < 1.0 && steps < 100) {
    mpm::update_damage<2>(law, s, kStrength, l, 0.3e-6, h2, d2);
    ++steps;
  }
  EXPECT_EQ(steps, 4);
}

// [HH17] §2.7: damage is incremented while the failure stress is exceeded. A particle that a
// transient peak lifted above σ_f for three steps and that unloaded since keeps d = 3 Δt/τ; the
// growth resumes when the stress exceeds σ_f again.
TEST(DamageLaw, TimeToFailureGrowsOnlyWhileTheStrengthIsExceeded) {
  const mpm::TimeToFailure law{1000.0};
  const double l = 1e-3, dt = 1e-7;  // τ = 1 µs, Δt/τ = 0.1
  mpm::Mat<2> s = mpm::Mat<2>::Zero();
  double history = 0.0, damage = 0.0;
  s(0, 0) = 1.5 * kStrength;
  for (int k = 0; k < 3; ++k) mpm::update_damage<2>(law, s, kStrength, l, dt, history, damage);
  EXPECT_NEAR(damage, 0.3, 1e-12);
  s(0, 0) = 0.5 * kStrength;  // the peak has passed
  for (int k = 0; k < 20; ++k) mpm::update_damage<2>(law, s, kStrength, l, dt, history, damage);
  EXPECT_NEAR(damage, 0.3, 1e-12);
  EXPECT_EQ(history, 1.5 * kStrength);  // the history still records the peak
  s(0, 0) = kStrength;
  mpm::update_damage<2>(law, s, kStrength, l, dt, history, damage);
  EXPECT_NEAR(damage, 0.4, 1e-12);
}

TEST(DamageLaw, WeibullMedianSizeEffectAndSeed) {
  mpm::WeibullStrength w;
  w.reference_strength = 100e6;
  w.reference_volume = 1e-9;  // 1 mm³
  w.modulus = 6.0;
  w.thickness = 1e-3;
  w.seed = 12345;
  const std::size_t n = 40000;
  const double area = 0.25e-6;  // 0.5 mm × 0.5 mm particles, V = 0.25 mm³ with 1 mm thickness
  const std::vector<double> volumes(n, area);
  std::vector<double> s = mpm::weibull_strengths(volumes, w, 2);
  ASSERT_EQ(s.size(), n);
  for (double v : s) ASSERT_TRUE(std::isfinite(v) && v > 0.0);

  // Median σ̄ (V̄/V)^{1/m}: the CDF is 1 − 2^{−(σ/σ_med)^m}, density at the median ln2 m / (2 σ_med),
  // so the sample median has standard error σ_med / (ln2 m √n) ≈ 1.2e-3 σ_med; allow 4 of them.
  const double median_expected = 100e6 * std::pow(1e-9 / (area * 1e-3), 1.0 / 6.0);
  EXPECT_DOUBLE_EQ(mpm::weibull_median_strength(area, w, 2), median_expected);
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const double se = median_expected / (std::log(2.0) * 6.0 * std::sqrt(static_cast<double>(n)));
  EXPECT_NEAR(median(s), median_expected, 4.0 * se);

  // Same seed → same strengths; another seed → different ones.
  EXPECT_EQ(mpm::weibull_strengths(volumes, w, 2), s);
  mpm::WeibullStrength w2 = w;
  w2.seed = 54321;
  EXPECT_NE(mpm::weibull_strengths(volumes, w2, 2), s);

  // Size effect: 8× the volume is weaker by 8^{-1/m}; in 3D the volume is used as given.
  const std::vector<double> big(n, 8.0 * area * 1e-3);
  const std::vector<double> s_big = mpm::weibull_strengths(big, w, 3);
  EXPECT_NEAR(median(s_big), median_expected * std::pow(8.0, -1.0 / 6.0), 4.0 * se);
  // With the same seed the draws are the same ℛ, so every strength scales exactly by 8^{-1/m}.
  for (std::size_t k = 0; k < 100; ++k)
    EXPECT_NEAR(s_big[k], s[k] * std::pow(8.0, -1.0 / 6.0), 1e-9 * s[k]);
}

// The solver's one-eigen-solve update equals degrade_stress and degradable_energy taken
// separately, for stretched, sheared and compressed states with a thermal pressure in the trial
// stress (isotropic, so coaxial with b).
TEST(DamageLaw, OneSpectralDecompositionGivesBothDegradedStressAndDegradableEnergy) {
  const mpm::NeoHookean m = glass();
  const double pressures[] = {0.0, -40e6, 25e6};
  for (double pressure : pressures)
    for (int k = 0; k < 50; ++k) {
      mpm::Mat<2> F;
      const double a = 0.002 * std::sin(1.3 * k), b = 0.0015 * std::cos(0.7 * k),
                   s = 0.001 * std::sin(2.1 * k);
      F << 1.0 + a, s, 0.5 * s, 1.0 + b;
      const mpm::Mat<2> trial = m.cauchy<2>(F) + pressure * mpm::Mat<2>::Identity();
      const double psi = m.energy_density<2>(F);
      for (const auto deg : {mpm::Degradation::tensile_spectral, mpm::Degradation::isotropic}) {
        const double d = 0.05 + 0.018 * k;
        const auto both = mpm::degrade_with_energy<2>(m, F, trial, d, deg, psi);
        const mpm::Mat<2> stress = mpm::degrade_stress<2>(trial, d, deg);
        EXPECT_NEAR((both.stress - stress).norm(), 0.0, 1e-9 * trial.norm() + 1e-6);
        EXPECT_NEAR(both.degradable, mpm::degradable_energy<2>(m, F, deg), 1e-9 * psi + 1e-9);
      }
    }
}

namespace {

/// First Piola–Kirchhoff stress P = J σ F⁻ᵀ of a particle at fixed damage, from the elastic law
/// the degradation acts on.
mpm::Mat<2> nominal_stress(const mpm::NeoHookean& m, const mpm::Mat<2>& F, double damage,
                           mpm::Degradation degradation) {
  mpm::Mat<2> trial;
  double psi;
  mpm::elastic_stress_and_energy<2>(m, F, degradation, trial, psi);
  const mpm::Mat<2> stress =
      mpm::degrade_with_energy<2>(m, F, trial, damage, degradation, psi).stress;
  return mpm::Mat<2>(F.determinant() * stress * F.inverse().transpose());
}

/// Work ∫ P : dF at fixed damage along an open path from I to a sheared and squeezed F (trapezoidal
/// rule), and the stored energy ψ − d ψ_t at its end: equal for a split that is a potential.
std::pair<double, double> open_path_work_and_stored(const mpm::NeoHookean& m, double damage,
                                                    mpm::Degradation degradation) {
  mpm::Mat<2> F = mpm::Mat<2>::Identity(), F_old = F;
  double work = 0.0;
  mpm::Mat<2> P_old = nominal_stress(m, F, damage, degradation);
  for (int k = 1; k <= 20000; ++k) {
    const double t = double(k) / 20000;
    F << 1.0 + 0.2 * t, 0.3 * t, 0.0, 1.0 - 0.35 * t;
    const mpm::Mat<2> P = nominal_stress(m, F, damage, degradation);
    work += 0.5 * (P + P_old).cwiseProduct(F - F_old).sum();
    F_old = F;
    P_old = P;
  }
  mpm::Mat<2> trial;
  double psi;
  mpm::elastic_stress_and_energy<2>(m, F, degradation, trial, psi);
  return {work, psi - damage * mpm::degradable_energy<2>(m, F, degradation)};
}

/// Net work per reference volume of a damaged particle (fixed d) around a closed, non-proportional
/// path of F: compress, shear, stretch, return. Trapezoidal rule on P = J σ F⁻ᵀ : dF with fine
/// steps.
double cycle_work(const mpm::NeoHookean& m, double damage, mpm::Degradation degradation) {
  auto path = [](double t) {  // t in [0, 4]: four legs, F(0) = F(4) = I
    mpm::Mat<2> F = mpm::Mat<2>::Identity();
    const double a = std::min(t, 1.0), b = std::clamp(t - 1.0, 0.0, 1.0),
                 c = std::clamp(t - 2.0, 0.0, 1.0), e = std::clamp(t - 3.0, 0.0, 1.0);
    F(1, 1) = 1.0 - 0.3 * a + 0.3 * c;  // squeeze in y, released in the third leg
    F(0, 1) = 0.4 * b - 0.4 * e;        // shear on, shear off in the fourth leg
    F(0, 0) = 1.0 + 0.5 * b - 0.5 * e;  // stretch in x with the shear
    return F;
  };
  auto nominal = [&](const mpm::Mat<2>& F) { return nominal_stress(m, F, damage, degradation); };
  const int n = 40000;
  double work = 0.0;
  mpm::Mat<2> F_old = path(0.0), P_old = nominal(F_old);
  for (int k = 1; k <= n; ++k) {
    const mpm::Mat<2> F = path(4.0 * k / n), P = nominal(F);
    work += 0.5 * (P + P_old).cwiseProduct(F - F_old).sum();
    F_old = F;
    P_old = P;
  }
  return work;
}

}  // namespace

TEST(DamageLaw, VolumetricDeviatoricSplitDerivesFromAPotential) {
  // [AMM09]: ψ_d = U·[J ≤ 1] + (1 − d)(W + U·[J > 1]) is a potential, so a closed deformation
  // cycle at fixed damage does no net work, and along any path the work equals the change of the
  // stored energy ψ − d ψ_t. The spectral split of the Cauchy stress ([HH17] eq. (26)-(27)) is not
  // a potential: the same cycle of a failed particle gives or takes energy that no term books.
  const mpm::NeoHookean m = glass();
  const double scale = m.shear_modulus;  // the cycle's strains are O(1): energies O(G)
  for (const double d : {0.0, 0.5, 1.0})
    EXPECT_NEAR(cycle_work(m, d, mpm::Degradation::volumetric_deviatoric), 0.0, 1e-6 * scale)
        << "d = " << d;
  EXPECT_GT(std::abs(cycle_work(m, 1.0, mpm::Degradation::tensile_spectral)), 1e-2 * scale);

  // Stored energy equals the work along an open path (start undeformed, end sheared and squeezed).
  const auto [work, stored] =
      open_path_work_and_stored(m, 0.7, mpm::Degradation::volumetric_deviatoric);
  EXPECT_NEAR(work, stored, 1e-6 * std::abs(stored));
}

TEST(DamageLaw, FailedParticleUnderTheVolumetricDeviatoricSplitCarriesOnlyPressure) {
  const mpm::NeoHookean m = glass();
  const auto failed = [&](const mpm::Mat<2>& F) {
    return mpm::degrade_with_energy<2>(
        m, F, m.cauchy<2>(F), 1.0, mpm::Degradation::volumetric_deviatoric, m.energy_density<2>(F));
  };
  // Sheared and squeezed (J < 1): the stress is the neo-Hookean pressure K ln J / J, isotropic.
  mpm::Mat<2> F;
  F << 1.5, 0.4, 0.0, 0.6;
  const double J = F.determinant();
  const auto squeezed = failed(F);
  const mpm::Mat<2> pressure = m.bulk_modulus * std::log(J) / J * mpm::Mat<2>::Identity();
  EXPECT_LT((squeezed.stress - pressure).norm(), 1e-9 * pressure.norm());
  // Its stored energy is U(J) = K/2 (ln J)² alone.
  EXPECT_NEAR(m.energy_density<2>(F) - squeezed.degradable,
              0.5 * m.bulk_modulus * std::log(J) * std::log(J), 1e-9 * m.bulk_modulus);
  // Stretched (J > 1): nothing is left.
  F << 1.5, 0.4, 0.0, 0.9;
  EXPECT_LT(failed(F).stress.norm(), 1e-9 * m.bulk_modulus);
  EXPECT_NEAR(failed(F).degradable, m.energy_density<2>(F), 1e-9 * m.bulk_modulus);
}

TEST(DamageLaw, HenckySpectralSplitDerivesFromAPotentialAndReleasesExactlyPsiPlus) {
  // ψ_d = ψ⁻ + (1 − d) ψ⁺ on the Hencky energy ([KT19] eq. (14)): a closed cycle at fixed d does
  // no net work, and along an open path at fixed d the work is ψ − d ψ⁺ with ψ⁺ the degradable
  // energy, so Δd ψ⁺ is the exact release.
  const mpm::NeoHookean m = glass();
  const double scale = m.shear_modulus;
  for (const double d : {0.0, 0.5, 1.0})
    EXPECT_NEAR(cycle_work(m, d, mpm::Degradation::hencky_spectral), 0.0, 1e-6 * scale)
        << "d = " << d;

  const auto [work, stored] = open_path_work_and_stored(m, 0.7, mpm::Degradation::hencky_spectral);
  EXPECT_NEAR(work, stored, 1e-6 * std::abs(stored));
}

TEST(DamageLaw, FailedParticleUnderTheHenckySplitResistsCompressionAndShearButNotTension) {
  const mpm::NeoHookean m = glass();
  const auto degradation = mpm::Degradation::hencky_spectral;
  const double lambda = m.bulk_modulus - 2.0 * m.shear_modulus / 3.0, mu = m.shear_modulus;
  const auto failed = [&](const mpm::Mat<2>& F) {
    mpm::Mat<2> trial;
    double psi;
    mpm::elastic_stress_and_energy<2>(m, F, degradation, trial, psi);
    return mpm::degrade_with_energy<2>(m, F, trial, 1.0, degradation, psi).stress;
  };
  // Squeezed along y, free along x (F = diag(1, 0.9)): ε = (0, ln 0.9), all compressive, so the
  // failed particle keeps the whole Hencky stress: σ_yy = (λ + 2μ) ln 0.9 / 0.9, σ_xx = λ ln 0.9 /
  // 0.9.
  mpm::Mat<2> F = mpm::Mat<2>::Identity();
  F(1, 1) = 0.9;
  const double e = std::log(0.9);
  EXPECT_NEAR(failed(F)(1, 1), (lambda + 2.0 * mu) * e / 0.9, 1e-9 * m.bulk_modulus);
  EXPECT_NEAR(failed(F)(0, 0), lambda * e / 0.9, 1e-9 * m.bulk_modulus);
  // Isochoric pure shear F = diag(1.1, 1/1.1): tr ε = 0, so only μ ε₂² survives in ψ⁻ and the
  // failed particle still resists the shear with σ_yy = 2μ ln(1/1.1) (J = 1), the compressed
  // direction.
  F << 1.1, 0.0, 0.0, 1.0 / 1.1;
  EXPECT_NEAR(failed(F)(1, 1), -2.0 * mu * std::log(1.1), 1e-9 * m.bulk_modulus);
  EXPECT_NEAR(failed(F)(0, 0), 0.0, 1e-9 * m.bulk_modulus);
  // Stretched in both directions: nothing is left.
  F << 1.1, 0.0, 0.0, 1.05;
  EXPECT_LT(failed(F).norm(), 1e-9 * m.bulk_modulus);
  // At small strain the Hencky trial stress is the neo-Hookean one to O(ε²).
  F << 1.0 + 1e-4, 2e-4, -1e-4, 1.0 - 3e-4;
  mpm::Mat<2> hencky;
  double psi;
  mpm::elastic_stress_and_energy<2>(m, F, degradation, hencky, psi);
  EXPECT_LT((hencky - m.cauchy<2>(F)).norm(), 1e-3 * m.cauchy<2>(F).norm());
}
