// Size-distribution fits against samples of known laws: Rosin-Rammler (d₀ = 50 µm, n = 1.5) and a
// truncated power law (D = 1.6), 2,000 samples each; the 95 % intervals' coverage over 100 seeded
// repetitions; the Clauset-Shalizi-Newman choice of d_min on a sample whose tail alone is a
// power law.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "fragmpm/analysis/size_fits.hpp"

using namespace fragmpm::analysis;

namespace {

constexpr double kD0 = 50e-6, kN = 1.5, kD = 1.6, kDmin = 10e-6, kDmax = 1e-3;

/// Inverse CDF: d = d₀ (−ln(1 − u))^(1/n).
std::vector<double> rosin_rammler_sample(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> d(count);
  for (double& x : d) x = kD0 * std::pow(-std::log1p(-u(rng)), 1.0 / kN);
  return d;
}

/// Inverse CDF of N(>d) ∝ d^(−D) on [d_min, d_max]: d = d_min (1 − u (1 − r^(−D)))^(−1/D).
std::vector<double> power_law_sample(std::size_t count, std::uint64_t seed, double d_max) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const double q = std::isfinite(d_max) ? std::pow(d_max / kDmin, -kD) : 0.0;
  std::vector<double> d(count);
  for (double& x : d) x = kDmin * std::pow(1.0 - u(rng) * (1.0 - q), -1.0 / kD);
  return d;
}

}  // namespace

TEST(SizeFits, QuantilesMatchTables) {
  EXPECT_NEAR(normal_quantile(0.975), 1.959963985, 1e-8);
  EXPECT_NEAR(normal_quantile(0.025), -1.959963985, 1e-8);
  // χ²(0.975; 100) = 129.561, χ²(0.025; 100) = 74.222 (tables).
  EXPECT_NEAR(chi_squared_quantile(0.975, 100) / 129.561, 1.0, 1e-3);
  EXPECT_NEAR(chi_squared_quantile(0.025, 100) / 74.222, 1.0, 1e-3);
}

TEST(SizeFits, RosinRammlerRecoversScaleAndExponentWithin3Percent) {
  const std::vector<double> d = rosin_rammler_sample(2000, 17);
  const RosinRammlerFit fit = fit_rosin_rammler(d);
  EXPECT_NEAR(fit.d0 / kD0, 1.0, 0.03);
  EXPECT_NEAR(fit.n / kN, 1.0, 0.03);
  EXPECT_LT(fit.n_ci.low, fit.n);
  EXPECT_GT(fit.n_ci.high, fit.n);
  // The interval half-width of n is about 1.96 × 0.78 n / √N (Weibull information) = 2.6 %.
  EXPECT_NEAR((fit.n_ci.high - fit.n_ci.low) / 2 / fit.n, 1.96 * 0.7797 / std::sqrt(2000.0), 0.003);
  EXPECT_EQ(fit.samples, 2000u);
  EXPECT_LT(fit.ks, 1.36 / std::sqrt(2000.0));  // KS 95 % critical value
}

TEST(SizeFits, TruncatedPowerLawRecoversExponentWithin3Percent) {
  const std::vector<double> d = power_law_sample(2000, 23, kDmax);
  const PowerLawFit fit = fit_power_law(d, kDmin, kDmax);
  EXPECT_NEAR(fit.exponent / kD, 1.0, 0.03);
  EXPECT_EQ(fit.tail, 2000u);
  // Ignoring the truncation at d_max/d_min = 100 biases D̂ up (the missing large sizes shorten
  // Σ ln(d/d_min)): the untruncated estimator must come out larger on the same sample.
  const PowerLawFit untruncated = fit_power_law(d, kDmin);
  EXPECT_GT(untruncated.exponent, fit.exponent);
}

TEST(SizeFits, NinetyFivePercentIntervalsCoverTheTruthInAtLeast90Of100Repetitions) {
  int rr_n = 0, rr_d0 = 0, pl = 0, pl_truncated = 0;
  for (std::uint64_t rep = 0; rep < 100; ++rep) {
    const RosinRammlerFit r = fit_rosin_rammler(rosin_rammler_sample(2000, 1000 + rep));
    rr_n += r.n_ci.low <= kN && kN <= r.n_ci.high;
    rr_d0 += r.d0_ci.low <= kD0 && kD0 <= r.d0_ci.high;
    const PowerLawFit p = fit_power_law(power_law_sample(2000, 5000 + rep, INFINITY), kDmin);
    pl += p.exponent_ci.low <= kD && kD <= p.exponent_ci.high;
    const PowerLawFit t = fit_power_law(power_law_sample(2000, 9000 + rep, kDmax), kDmin, kDmax);
    pl_truncated += t.exponent_ci.low <= kD && kD <= t.exponent_ci.high;
  }
  std::printf("coverage of 100: RR n %d, RR d0 %d, power law %d, truncated power law %d\n", rr_n,
              rr_d0, pl, pl_truncated);
  EXPECT_GE(rr_n, 90);
  EXPECT_GE(rr_d0, 90);
  EXPECT_GE(pl, 90);
  EXPECT_GE(pl_truncated, 90);
}

TEST(SizeFits, ClausetShaliziNewmanFindsWhereThePowerLawTailStarts) {
  // 1,000 sizes uniform on [1, 10) µm below a power-law tail of 2,000 sizes from 10 µm up: the
  // KS criterion must put d_min near 10 µm, not in the uniform body.
  std::vector<double> d = power_law_sample(2000, 31, INFINITY);
  std::mt19937_64 rng(37);
  std::uniform_real_distribution<double> body(1e-6, kDmin);
  for (int i = 0; i < 1000; ++i) d.push_back(body(rng));
  const PowerLawFit fit = fit_power_law_csn(d);
  EXPECT_GT(fit.d_min, 0.9 * kDmin);
  EXPECT_LT(fit.d_min, 1.5 * kDmin);
  EXPECT_NEAR(fit.exponent / kD, 1.0, 0.06);
  EXPECT_LT(fit.tail, 2001u);
}

TEST(SizeFits, RefusesDegenerateSamples) {
  EXPECT_THROW(fit_rosin_rammler(std::vector<double>{1.0, 2.0}), std::invalid_argument);
  EXPECT_THROW(fit_rosin_rammler(std::vector<double>{1.0, 1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(fit_rosin_rammler(std::vector<double>{1.0, -2.0, 3.0}), std::invalid_argument);
  EXPECT_THROW(fit_power_law(std::vector<double>{1.0, 2.0}, 0.0), std::invalid_argument);
}
