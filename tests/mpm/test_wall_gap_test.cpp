// A contact wall with `gap_test` touches material where the material is ([NBS18] eq. (8) with the
// wall as the partner; walls.cpp): a platen moving onto a block at rest first pushes when its plane
// comes within wall_gap_cells of the material position of the nodes next to the surface, not when
// it passes the first node that carries mass.
#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"

using namespace fragmpm;

namespace {

// Cells of 1 mm with nodes on whole millimetres; 2 × 2 particles per cell, so the block's top
// particles sit at y = 5.25 mm and its surface at 5.5 mm, half-way between the node lines 5 and
// 6 mm. The platen starts at 7 mm and moves down at 10 m/s.
const char* platen_onto_block = R"(
[grid]
cell_size = "1 mm"
min = ["-3 mm", "-3 mm"]
max = ["13 mm", "9 mm"]
particles_per_cell = 2
[time]
cfl = 0.4
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
max = ["10 mm", "5.5 mm"]
[[walls]]
name = "platen"
point = ["0 mm", "7 mm"]
normal = [0, -1]
velocity = { type = "constant", value = ["0 m/s", "-10 m/s"] }
[stop]
max_steps = 10000
)";

constexpr double surface = 5.5e-3, platen_start = 7e-3, platen_speed = 10.0;

/// Height of the platen's plane at the first step with a non-zero platen force [m].
std::optional<double> first_contact_height(bool gap_test) {
  std::string text = platen_onto_block;
  if (gap_test) text.insert(text.find("velocity = {"), "gap_test = true\n");
  auto problem = pipeline::parse_scene(text, "platen-onto-block.toml");
  EXPECT_EQ(problem.walls[0].gap_test, gap_test);
  mpm::Solver<2> solver(std::move(problem));
  while (solver.time() < 0.2e-3) {
    EXPECT_FALSE(solver.step().has_value());
    if (solver.last_row().wall_force[0].norm() > 0.0)
      return platen_start - platen_speed * solver.time();
  }
  return std::nullopt;
}

}  // namespace

TEST(WallGapTest, PlatenTouchesTheMaterialNotTheFirstNodeWithMass) {
  // Node positions: the node row at 6 mm carries mass from the top particles (5.25 mm lies in its
  // support [5, 7] mm), so a wall tested on node positions pushes once its plane passes 6 mm,
  // half a cell above the surface. With the gap test that row's material position is 5.25 mm,
  // and it touches once the plane is within 0.4 mm of it, at 5.65 mm: 0.15 mm above the surface
  // (the first step at or below; a step moves the platen about 0.01 mm).
  const auto by_node = first_contact_height(false);
  const auto by_material = first_contact_height(true);
  ASSERT_TRUE(by_node.has_value());
  ASSERT_TRUE(by_material.has_value());
  EXPECT_NEAR(*by_node - surface, 0.5e-3, 0.02e-3);
  EXPECT_NEAR(*by_material - surface, 0.15e-3, 0.02e-3);
}

TEST(WallGapTest, OnlyContactWallsTakeIt) {
  std::string roller = platen_onto_block;
  roller.insert(roller.find("velocity = {"), "kind = \"roller\"\ngap_test = true\n");
  try {
    pipeline::parse_scene(roller, "platen-onto-block.toml");
    ADD_FAILURE() << "a roller wall accepted gap_test";
  } catch (const pipeline::SceneError& e) {
    EXPECT_NE(std::string(e.what()).find("gap_test"), std::string::npos) << e.what();
  }
}

TEST(WallGapTest, TheModuleLogNamesAMovingWallThatAdvancesByCells) {
  // The platen moves along its normal: without the gap test the log warns that it advances one
  // cell at a time; with it the log says the wall touches by position. A fixed wall is not named.
  auto walls_line = [](const std::string& text) {
    for (const auto& m : mpm::plan_modules<2>(pipeline::parse_scene(text, "platen.toml")))
      if (m.module == "walls") return m.reason;
    return std::string();
  };
  std::string gap_tested = platen_onto_block;
  gap_tested.insert(gap_tested.find("velocity = {"), "gap_test = true\n");
  std::string fixed = platen_onto_block;
  fixed.replace(fixed.find("\"-10 m/s\""), 9, "\"0 m/s\"");
  const std::string by_node = walls_line(platen_onto_block);
  const std::string by_material = walls_line(gap_tested);
  EXPECT_NE(by_node.find("'platen' without gap_test"), std::string::npos) << by_node;
  EXPECT_EQ(by_material.find("without gap_test"), std::string::npos) << by_material;
  EXPECT_NE(by_material.find("'platen' touch"), std::string::npos) << by_material;
  EXPECT_EQ(walls_line(fixed).find("'platen'"), std::string::npos) << walls_line(fixed);
}
