// Mass-proportional grid damping ([time] damping, step/grid_update.cpp): a free rigid motion decays
// exactly as (1 + α Δt)^(−n), which tends to the closed form exp(−α t) of m v̇ = −α m v; α = 0
// leaves the motion untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

using namespace fragmpm;
using mpm::Vec;

namespace {

const char* drifting_block = R"(
[grid]
cell_size = "1 mm"
min = ["-10 mm", "-10 mm"]
max = ["40 mm", "30 mm"]
particles_per_cell = 2
[time]
dt = "20 ns"
damping = "2e5 1/s"
[[materials]]
name = "steel"
E = "200 GPa"
nu = 0.3
density = "7.8 g/cm3"
[[bodies]]
name = "block"
material = "steel"
shape = "box"
min = ["0 mm", "0 mm"]
max = ["10 mm", "6 mm"]
velocity = ["3 m/s", "-2 m/s"]
[stop]
max_steps = 1000
)";

Vec<2> velocity_after(mpm::Problem<2> problem, int steps) {
  mpm::Solver<2> solver(std::move(problem));
  for (int n = 0; n < steps; ++n) EXPECT_FALSE(solver.step().has_value());
  const auto& P = solver.particles();
  Vec<2> largest_deviation = Vec<2>::Zero();
  for (std::size_t p = 1; p < P.size(); ++p)
    largest_deviation = largest_deviation.cwiseMax((P.v[p] - P.v[0]).cwiseAbs());
  EXPECT_LT(largest_deviation.norm(), 1e-12) << "the damped motion must stay rigid";
  return P.v[0];
}

}  // namespace

TEST(GridDamping, RigidMotionDecaysAtTheDiscreteRate) {
  const auto problem = pipeline::parse_scene(drifting_block, "drifting-block.toml");
  ASSERT_DOUBLE_EQ(problem.time.damping, 2e5);
  const double dt = problem.time.fixed_dt, alpha = problem.time.damping;
  const int steps = 250;  // t = 5 µs, α t = 1
  const Vec<2> v = velocity_after(problem, steps);
  const double discrete = std::pow(1.0 + alpha * dt, -steps);
  EXPECT_NEAR(v.x(), 3.0 * discrete, 1e-12);
  EXPECT_NEAR(v.y(), -2.0 * discrete, 1e-12);
  // The closed form exp(−α t) to first order in α Δt = 0.004: ln ratio = n (αΔt − ln(1 + αΔt)).
  const double closed_form = std::exp(-alpha * dt * steps);
  EXPECT_NEAR(v.x() / 3.0, closed_form, 0.5 * alpha * dt * closed_form);
}

TEST(GridDamping, OffLeavesTheMotionUntouched) {
  auto problem = pipeline::parse_scene(drifting_block, "drifting-block.toml");
  problem.time.damping = 0.0;
  const Vec<2> v = velocity_after(problem, 50);
  EXPECT_NEAR(v.x(), 3.0, 1e-12);
  EXPECT_NEAR(v.y(), -2.0, 1e-12);
}

TEST(GridDamping, SceneRefusesNegativeDamping) {
  std::string text = drifting_block;
  text.replace(text.find("\"2e5 1/s\""), 9, "\"-1 1/s\"");
  try {
    pipeline::parse_scene(text, "drifting-block.toml");
    ADD_FAILURE() << "a negative damping coefficient was accepted";
  } catch (const pipeline::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("damping"), std::string::npos) << e.what();
  }
}
