// Two-field contact inside the full step: distinct bodies are separable from the first step through
// their surface flags ([HH17] §2.4), so two elastic disks that collide rebound without
// interpenetrating and slide past each other without friction, while single-field MPM is no-slip;
// the contact keeps momentum.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

using namespace fragmpm;
using mpm::Vec;

namespace {

std::string two_disks(const std::string& partitioning) {
  return R"(
[grid]
cell_size = "1 mm"
min = ["-14 mm", "-10 mm"]
max = ["14 mm", "10 mm"]
particles_per_cell = 2
[time]
cfl = 0.4
[[materials]]
name = "polymer"
E = "1 GPa"
nu = 0.3
density = "1000 kg/m3"
[[bodies]]
name = "left"
material = "polymer"
shape = "disk"
center = ["-6 mm", "0 mm"]
radius = "5 mm"
velocity = ["10 m/s", "2 m/s"]
[[bodies]]
name = "right"
material = "polymer"
shape = "disk"
center = ["6 mm", "0 mm"]
radius = "5 mm"
velocity = ["-10 m/s", "-2 m/s"]
[contact]
friction = 0.0
partitioning = ")" +
         partitioning + R"("
[stop]
end_time = "90 us"
)";
}

struct CollisionOutcome {
  double deepest_penetration =
      -std::numeric_limits<double>::infinity();  ///< largest crossing of the mid-plane by either
                                                 ///< disk [m]
  double largest_momentum = 0.0;                 ///< max |Σ m v| over the run [kg m/s per m]
  double momentum_scale = 0.0;                   ///< Σ m |v| at the start
  double final_left_velocity =
      0.0;                          ///< centre-of-mass x-velocity of the left disk at the end [m/s]
  double final_left_sliding = 0.0;  ///< its y-velocity at the end (2 m/s at the start) [m/s]
};

CollisionOutcome collide(const std::string& partitioning) {
  auto problem = pipeline::parse_scene(two_disks(partitioning), "two-disks.toml");
  CollisionOutcome out;
  for (std::size_t p = 0; p < problem.particles.size(); ++p)
    out.momentum_scale += problem.particles.mass[p] * problem.particles.v[p].norm();
  mpm::Solver<2> solver(std::move(problem));
  while (solver.time() < solver.problem().stop.end_time) {
    const auto failure = solver.step(solver.problem().stop.end_time - solver.time());
    EXPECT_FALSE(failure.has_value()) << failure->what;
    if (failure) break;
    const auto& P = solver.particles();
    for (std::size_t p = 0; p < P.size(); ++p) {
      // Particle centres sit half a spacing (0.125 mm) inside the disk edge.
      const double crossing = P.body[p] == 0 ? P.x[p][0] : -P.x[p][0];
      out.deepest_penetration = std::max(out.deepest_penetration, crossing);
    }
    out.largest_momentum = std::max(out.largest_momentum, solver.last_row().momentum.norm());
  }
  const auto& P = solver.particles();
  double mass = 0.0;
  Vec<2> momentum = Vec<2>::Zero();
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.body[p] == 0) {
      mass += P.mass[p];
      momentum += P.mass[p] * P.v[p];
    }
  out.final_left_velocity = momentum[0] / mass;
  out.final_left_sliding = momentum[1] / mass;
  return out;
}

}  // namespace

TEST(ContactSolver, CollidingDisksReboundWithoutInterpenetration) {
  const CollisionOutcome partitioned = collide("auto");
  // No particle centre crosses the mid-plane (contact acts one cell before the surfaces meet).
  EXPECT_LT(partitioned.deepest_penetration, 0.0);
  // Momentum is exchanged pairwise at every node: it stays zero to round-off.
  EXPECT_LT(partitioned.largest_momentum, 1e-12 * partitioned.momentum_scale);
  // Elastic disks rebound: the left disk ends moving left.
  EXPECT_LT(partitioned.final_left_velocity, -2.0);

  // Frictionless contact exerts no tangential force: the disks slide past each other keeping their
  // opposite 2 m/s (the contact normal tilts by at most the 2/10 velocity angle).
  EXPECT_NEAR(partitioned.final_left_sliding, 2.0, 0.1);

  const CollisionOutcome single_field = collide("off");
  // One velocity field is no-slip contact: while touching, the disks share nodal velocities and
  // the tangential sliding is largely lost.
  EXPECT_LT(single_field.final_left_sliding, 1.5);
}
