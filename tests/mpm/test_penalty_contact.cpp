// Penalty walls ([XLS21] eq. (83), (86)-(87); fragmpm/mpm/penalty_contact.hpp): the measure of a
// particle domain behind a plane against closed-form areas, and a block relaxed on a penalty wall
// whose reaction must equal its weight.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "fragmpm/mpm/penalty_contact.hpp"
#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

using namespace fragmpm;
using mpm::Mat;
using mpm::Vec;

TEST(PenaltyContact, UnitCubeFractions) {
  // 2D: the triangle u + v ≤ c has area c²/2 for c ≤ 1, and 1 − (2 − c)²/2 above.
  EXPECT_NEAR(mpm::unit_cube_fraction_below<2>(Vec<2>(1, 1), 0.5), 0.125, 1e-15);
  EXPECT_NEAR(mpm::unit_cube_fraction_below<2>(Vec<2>(1, 1), 1.5), 0.875, 1e-15);
  // An edge parallel to the plane: the fraction is linear in c.
  EXPECT_NEAR(mpm::unit_cube_fraction_below<2>(Vec<2>(0, 2), 0.5), 0.25, 1e-15);
  // Negative components flip: −u ≤ −0.75 ⟺ u ≥ 0.75.
  EXPECT_NEAR(mpm::unit_cube_fraction_below<2>(Vec<2>(-1, 0), -0.75), 0.25, 1e-15);
  EXPECT_EQ(mpm::unit_cube_fraction_below<2>(Vec<2>(1, 1), -0.1), 0.0);
  EXPECT_EQ(mpm::unit_cube_fraction_below<2>(Vec<2>(1, 1), 2.1), 1.0);
  // 3D: the corner tetrahedron u + v + w ≤ c has volume c³/6.
  EXPECT_NEAR(mpm::unit_cube_fraction_below<3>(Vec<3>(1, 1, 1), 0.5), 0.125 / 6.0, 1e-15);
  EXPECT_NEAR(mpm::unit_cube_fraction_below<3>(Vec<3>(1, 1, 1), 1.5), 0.5, 1e-15);
}

TEST(PenaltyContact, DomainAreaBehindAPlane) {
  const Vec<2> floor(0.0, 0.0), up(0.0, 1.0);
  Mat<2> square;
  square << 2.0, 0.0, 0.0, 2.0;  // r1 = (2, 0), r2 = (0, 2)
  // Centre 0.25 above the floor: the lowest 0.75 of a 2-wide square is behind it.
  EXPECT_NEAR(mpm::penetration_measure<2>(Vec<2>(5.0, 0.25), square, floor, up), 1.5, 1e-14);
  EXPECT_EQ(mpm::penetration_measure<2>(Vec<2>(5.0, 1.0), square, floor, up), 0.0);
  EXPECT_NEAR(mpm::penetration_measure<2>(Vec<2>(5.0, -3.0), square, floor, up), 4.0, 1e-14);
  // A parallelogram with a sloped bottom edge from (−1, −0.5) to (1, 0.5) (r1 = (2, 1),
  // r2 = (0, 2), centre (0, 1)): a triangle of legs 1 and 0.5 is behind the floor.
  Mat<2> sheared;
  sheared << 2.0, 0.0, 1.0, 2.0;
  EXPECT_NEAR(mpm::penetration_measure<2>(Vec<2>(0.0, 1.0), sheared, floor, up), 0.25, 1e-14);
  // The same area behind a tilted plane seen from a rotated frame.
  const double angle = 0.3;
  Mat<2> rotation;
  rotation << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  EXPECT_NEAR(mpm::penetration_measure<2>(rotation * Vec<2>(0.0, 1.0), rotation * sheared, floor,
                                          rotation * up),
              0.25, 1e-14);
}

namespace {

const char* block_on_penalty_wall = R"(
[grid]
cell_size = "1 mm"
min = ["-3 mm", "-3 mm"]
max = ["13 mm", "9 mm"]
particles_per_cell = 2
[time]
cfl = 0.4
damping = "2e5 1/s"
pic_fraction = 1.0
[physics]
gravity = ["0 m/s2", "-1e5 m/s2"]
[[materials]]
name = "soft"
E = "100 MPa"
nu = 0.25
density = "1 g/cm3"
[[bodies]]
name = "block"
material = "soft"
shape = "box"
min = ["0 mm", "0 mm"]
max = ["10 mm", "5 mm"]
[[walls]]
name = "floor"
point = ["0 mm", "0 mm"]
normal = [0, 1]
kind = "penalty"
stiffness = "1 GPa/mm"
[stop]
max_steps = 10000
)";

}  // namespace

TEST(PenaltyContact, BlockSettlesWithReactionEqualToItsWeight) {
  auto problem = pipeline::parse_scene(block_on_penalty_wall, "penalty-block.toml");
  ASSERT_EQ(problem.walls[0].kind, mpm::WallKind::penalty);
  ASSERT_DOUBLE_EQ(problem.walls[0].penalty_stiffness, 1e12);
  double weight = 0.0;
  for (double m : problem.particles.mass) weight += m * 1e5;
  mpm::Solver<2> solver(std::move(problem));
  for (int n = 0; n < 4000; ++n) ASSERT_FALSE(solver.step().has_value());
  const double reaction = -solver.last_row().wall_force[0].y();
  EXPECT_NEAR(reaction, weight, 1e-4 * weight);  // 5000 N/m
  EXPECT_LT(solver.last_row().kinetic, 1e-6 * solver.last_row().strain);
  // The floor holds the block with a uniform penetration δ = weight / (κ_n × width).
  const double expected_penetration = weight / (1e12 * 10e-3);
  double lowest = 0.0;
  const auto& P = solver.particles();
  for (std::size_t p = 0; p < P.size(); ++p)
    lowest = std::min(
        lowest, P.x[p].y() - 0.5 * (std::abs(P.domain[p](1, 0)) + std::abs(P.domain[p](1, 1))));
  EXPECT_NEAR(-lowest, expected_penetration, 0.1 * expected_penetration);
}

TEST(PenaltyContact, SceneKeys) {
  const auto refused_at = [](const std::string& text, const std::string& key) {
    try {
      pipeline::parse_scene(text, "penalty-block.toml");
      ADD_FAILURE() << "accepted a scene that should fail at '" << key << "'";
    } catch (const pipeline::SceneError& e) {
      EXPECT_NE(std::string(e.what()).find(key), std::string::npos) << e.what();
    }
  };
  const std::string text = block_on_penalty_wall;
  const std::string stiffness = "stiffness = \"1 GPa/mm\"\n";
  std::string without = text;
  without.erase(without.find(stiffness), stiffness.size());
  refused_at(without, "stiffness");  // a penalty wall needs κ_n
  std::string roller = text;
  roller.replace(roller.find("\"penalty\""), 9, "\"roller\"");
  refused_at(roller, "stiffness");  // only penalty walls have one
  std::string wrong_unit = text;
  wrong_unit.replace(wrong_unit.find("\"1 GPa/mm\""), 10, "\"1 GPa\"");
  refused_at(wrong_unit, "stiffness");  // a pressure is not a pressure per length
}
