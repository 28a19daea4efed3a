// Particles that leave the domain with `[grid] outside = "remove"`: a pellet shot out of a small
// domain is removed while the run goes on, its mass and kinetic energy are booked exactly, and the
// energy balance and momentum of the run equal those of the same run in a larger domain, where the
// pellet flies on. With "stop" the departure ends the run, and a departure faster than ten times
// the largest wave speed ends it even with "remove".
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "../support/departure_scene.hpp"
#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

using namespace fragmpm;
using mpm::Vec;

namespace {

mpm::Problem<2> problem(const std::string& max_x, const std::string& outside) {
  mpm::Problem<2> p =
      pipeline::parse_scene(test_support::departure_scene(max_x, outside, 1000), "departure.toml");
  // A vibration of the block, so that its strain energy and the balance are not trivial.
  for (std::size_t k = 0; k < p.particles.size(); ++k)
    if (p.particles.body[k] == 1)
      p.particles.v[k] +=
          Vec<2>(std::sin(std::numbers::pi * (p.particles.x[k][0] - 2e-3) / 0.01), 0.0);
  return p;
}

/// Steps the pellet needs from x = 25.25 mm to beyond 30 mm at 100 m/s and Δt = 0.05 µs: 950.
/// (Δt is C = 0.42 of the limit h / (√2 (c + |v|)): a particle alone in its cells, whose outer
/// nodes carry a tiny share of its mass, is not stable up to C = 1.)
constexpr int kDepartureStep = 950;

}  // namespace

TEST(Departures, RemovedPelletIsBookedAndTheBalanceIsUnchanged) {
  mpm::Solver<2> removing(problem("30 mm", "remove"));
  mpm::Solver<2> flying_on(problem("60 mm", "stop"));
  const std::size_t n = removing.particles().size();
  ASSERT_EQ(removing.particles().body[0], 0);
  const double pellet_mass = removing.particles().mass[0];
  // ρ s² with s = 0.5 mm.
  EXPECT_NEAR(pellet_mass, 7800.0 * 0.25e-6, 1e-15);
  const double input = flying_on.last_row().totals.initial_energy;

  bool removed = false;
  double largest_difference = 0.0;
  for (int s = 1; s <= kDepartureStep + 50; ++s) {
    ASSERT_FALSE(removing.step()) << "step " << s;
    ASSERT_FALSE(flying_on.step()) << "step " << s;
    const mpm::SeriesRow<2>& a = removing.last_row();
    const mpm::SeriesRow<2>& b = flying_on.last_row();
    const mpm::LostParticles& lost = a.totals.lost;
    if (!removed && lost.count > 0) {
      removed = true;
      EXPECT_GE(s, kDepartureStep - 1);
      EXPECT_LE(s, kDepartureStep + 1);
      EXPECT_EQ(lost.count, 1);
      EXPECT_EQ(removing.particles().size(), n - 1);
      // The run that keeps the pellet is the same computation up to this step: the pellet left
      // with the state it has there.
      const auto& P = flying_on.particles();
      EXPECT_EQ(lost.mass, pellet_mass);
      EXPECT_EQ(lost.kinetic, 0.5 * P.mass[0] * P.v[0].squaredNorm());
      EXPECT_NEAR(lost.kinetic, 0.5 * pellet_mass * 100.0 * 100.0, 1e-12 * lost.kinetic);
      EXPECT_EQ(lost.momentum[0], P.mass[0] * P.v[0][0]);
      EXPECT_EQ(lost.momentum[1], P.mass[0] * P.v[0][1]);
      // A free particle keeps F = I up to round-off: no stored energy leaves with it.
      EXPECT_LT(std::abs(lost.strain), 1e-12 * lost.kinetic);
      for (std::size_t p = 0; p + 1 < n; ++p)
        ASSERT_EQ(removing.particles().id[p], static_cast<std::int32_t>(p + 1));
    }
    largest_difference = std::max(largest_difference, std::abs(a.balance_error - b.balance_error));
    const Vec<2> momentum_a =
        a.momentum + Vec<2>(a.totals.lost.momentum[0], a.totals.lost.momentum[1]);
    EXPECT_LT((momentum_a - b.momentum).norm(), 1e-12 * pellet_mass * 100.0) << "step " << s;
  }
  ASSERT_TRUE(removed);
  // The balance error of the run (2.4 mJ/m of 9.9 J/m of input) is the same whether the pellet is
  // removed or flies on, up to the round-off of the sums (2.5e-14 J/m): the pellet's 9.75 J/m of
  // kinetic energy is in `kinetic` in one run and in `lost_kinetic` in the other.
  EXPECT_GT(std::abs(flying_on.last_row().balance_error), 1e-6 * input);
  EXPECT_LT(largest_difference, 1e-12 * input);
}

TEST(Departures, StopEndsTheRunWhenTheParticleLeaves) {
  mpm::Solver<2> solver(problem("30 mm", "stop"));
  std::optional<mpm::NumericalFailure> failure;
  for (int s = 1; s <= kDepartureStep + 5 && !failure; ++s) failure = solver.step();
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->particle, 0);
  EXPECT_NE(failure->what.find("left the computational domain"), std::string::npos)
      << failure->what;
  EXPECT_NE(failure->what.find("outside = \"remove\""), std::string::npos) << failure->what;
}

TEST(Departures, AnImplausiblyFastDepartureStopsTheRunEvenWithRemove) {
  // Steel: c = √((K + 4G/3)/ρ) = √(269.2 GPa / 7800 kg/m³) = 5875 m/s; the bound is 10 c.
  const double K = 200e9 / (3 * (1 - 2 * 0.3)), G = 200e9 / (2 * 1.3);
  const double c = std::sqrt((K + 4 * G / 3) / 7800.0);
  mpm::Problem<2> p = problem("30 mm", "remove");
  p.particles.v[0] = Vec<2>(10.5 * c, 0.0);
  p.time.fixed_dt = 1e-9;
  mpm::Solver<2> solver(std::move(p));
  std::optional<mpm::NumericalFailure> failure;
  for (int s = 1; s <= 200 && !failure; ++s) failure = solver.step();
  ASSERT_TRUE(failure);
  EXPECT_EQ(failure->particle, 0);
  EXPECT_NE(failure->what.find("more than 10 times the largest wave speed"), std::string::npos)
      << failure->what;
  EXPECT_EQ(solver.accumulators().lost.count, 0);
  // Just below the bound the pellet is removed and the run goes on.
  mpm::Problem<2> q = problem("30 mm", "remove");
  q.particles.v[0] = Vec<2>(9.5 * c, 0.0);
  q.time.fixed_dt = 1e-9;
  mpm::Solver<2> slower(std::move(q));
  for (int s = 1; s <= 200; ++s) ASSERT_FALSE(slower.step()) << "step " << s;
  EXPECT_EQ(slower.accumulators().lost.count, 1);
}
