// Pooled CDFs with member-bootstrap bands: the pooled CDF itself, reproducibility from the seed,
// and bands that narrow as 1/√M when members are added.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "fragmpm/analysis/bootstrap_cdf.hpp"

using namespace fragmpm::analysis;

namespace {

/// M members of 200 fragments each; each member's sizes are exponential with a mean that varies
/// from member to member (lognormal, σ = 0.3), as Weibull realisations do.
std::vector<MemberSample> members(std::size_t M, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::lognormal_distribution<double> scale(0.0, 0.3);
  std::vector<MemberSample> out(M);
  for (MemberSample& m : out) {
    std::exponential_distribution<double> size(1.0 / scale(rng));
    for (int i = 0; i < 200; ++i) {
      const double d = size(rng);
      m.value.push_back(d);
      m.mass.push_back(d * d);
    }
  }
  return out;
}

double mean_width(const CdfBand& b) {
  double w = 0;
  for (std::size_t i = 0; i < b.x.size(); ++i) w += b.number_high[i] - b.number_low[i];
  return w / double(b.x.size());
}

}  // namespace

TEST(BootstrapCdf, PooledCdfOfTwoMembers) {
  const std::vector<MemberSample> m{{{1.0, 3.0}, {1.0, 1.0}}, {{2.0}, {2.0}}};
  const std::vector<double> x{0.5, 1.0, 2.5, 3.0};
  const CdfBand b = bootstrap_cdf_band(m, x, 200, 1);
  EXPECT_DOUBLE_EQ(b.number[0], 0.0);
  EXPECT_DOUBLE_EQ(b.number[1], 1.0 / 3.0);
  EXPECT_DOUBLE_EQ(b.number[2], 2.0 / 3.0);
  EXPECT_DOUBLE_EQ(b.number[3], 1.0);
  EXPECT_DOUBLE_EQ(b.mass[1], 0.25);
  EXPECT_DOUBLE_EQ(b.mass[2], 0.75);
  for (std::size_t i = 0; i < x.size(); ++i) {
    EXPECT_LE(b.number_low[i], b.number[i] + 1e-12);
    EXPECT_GE(b.number_high[i], b.number[i] - 1e-12);
  }
}

TEST(BootstrapCdf, SameSeedSameBandsOtherSeedOtherBands) {
  const auto m = members(8, 3);
  const auto x = spaced_points(0.05, 4.0, 40, true);
  const CdfBand a = bootstrap_cdf_band(m, x, 500, 42), b = bootstrap_cdf_band(m, x, 500, 42),
                c = bootstrap_cdf_band(m, x, 500, 43);
  EXPECT_EQ(a.number_low, b.number_low);
  EXPECT_EQ(a.mass_high, b.mass_high);
  EXPECT_NE(a.number_low, c.number_low);
}

TEST(BootstrapCdf, BandWidthFallsAsOneOverRootM) {
  const auto x = spaced_points(0.05, 4.0, 60, true);
  // The spread between 8 members is itself uncertain (a variance from 7 degrees of freedom, ±27 %
  // in width), so the widths are averaged over 40 independent studies per M.
  constexpr int studies = 40;
  double w8 = 0, w32 = 0;
  for (std::uint64_t s = 0; s < studies; ++s) {
    w8 += mean_width(bootstrap_cdf_band(members(8, 100 + s), x, 1000, 7 + s));
    w32 += mean_width(bootstrap_cdf_band(members(32, 200 + s), x, 1000, 7 + s));
  }
  const double ratio = w8 / w32;
  std::printf("band width M = 8: %.4f, M = 32: %.4f, ratio %.3f (1/sqrt(M) predicts 2)\n",
              w8 / studies, w32 / studies, ratio);
  EXPECT_NEAR(ratio / 2.0, 1.0, 0.2);
}
