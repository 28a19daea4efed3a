// Issue 4 (thermo-mechanical coupling): the P3 disk-squish scenes and the hot-interface stability
// scene. Frictional heat equals friction work ([XLS21] eq. (14), (82)); friction vanishes at θ_dam
// ([XLS21] eq. (15)).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>
#include <string>
#include <variant>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"

namespace fp = fragmpm::pipeline;
namespace mpm = fragmpm::mpm;

namespace {

/// The first `end` seconds of a disk-squish variant with Δt = 1e-7 s (below the CFL limit of
/// ≈ 1.8e-7 s at 1 mm) instead of the paper's 2e-8 s, so the start of the squeeze fits a unit test.
mpm::Solver<2> squish_start(const std::string& variant, const std::string& end,
                            std::map<std::string, std::string> extra = {}) {
  extra["time.dt"] = "1e-7";
  extra["stop.end_time"] = end;
  extra["output.interval"] = "0.0";
  const std::string name = "paper/disk-squish-" + variant + ".toml";
  mpm::Problem<2> problem =
      fp::parse_scene(fp::with_overrides(fp::embedded_scene(name), extra), name);
  mpm::Solver<2> solver(std::move(problem));
  while (solver.time() < solver.problem().stop.end_time * (1.0 - 1e-12)) {
    auto failure = solver.step(solver.problem().stop.end_time - solver.time());
    if (failure) ADD_FAILURE() << failure->what;
    if (failure) break;
  }
  return solver;
}

}  // namespace

TEST(DiskSquish, ScenesParseWithTheP3Parameters) {
  for (const std::string variant : {"isothermal", "coupled", "softening"}) {
    const std::string name = "paper/disk-squish-" + variant + ".toml";
    const mpm::Problem<2> problem = fp::parse_scene(fp::embedded_scene(name), name);
    EXPECT_EQ(problem.body_names.size(), 3u);
    EXPECT_NEAR(problem.particles.size(), 2900.0, 150.0) << variant;  // [XLS21] §4.4: 2905
    EXPECT_DOUBLE_EQ(problem.time.fixed_dt, 2e-8);
    EXPECT_DOUBLE_EQ(problem.grid.cell_size, 1e-3);
    EXPECT_EQ(problem.thermal.active(), variant != "isothermal") << variant;
    const auto& m = problem.materials.at(0);
    // E = 9KG/(3K + G) = 2.25 GPa, ν = 0.125 ([XLS21] Table 3).
    EXPECT_NEAR(9 * m.bulk_modulus * m.shear_modulus / (3 * m.bulk_modulus + m.shear_modulus),
                2.25e9, 1.0);
    EXPECT_EQ(std::holds_alternative<mpm::ThermalSofteningFriction>(problem.contact.friction),
              variant == "softening");
  }
}

// Without thermal expansion there is no structural heating, walls are frictionless and nothing
// damages: the heat content Σ m c (θ − θ₀) must equal the friction work booked between the bodies.
TEST(DiskSquish, FrictionalHeatEqualsFrictionWork) {
  const mpm::Solver<2> solver =
      squish_start("coupled", "3e-5", {{"materials[0].expansion", "0.0"}});
  const auto& row = solver.last_row();
  ASSERT_GT(row.totals.friction_work, 1.0);  // J/m: the wedge face has slid along the disk
  EXPECT_NEAR(row.thermal, row.totals.friction_work, 1e-9 * row.totals.friction_work);
  const auto& T = solver.particles().temperature;
  EXPECT_GT(*std::max_element(T.begin(), T.end()), 293.15 + 1.0);  // the contact has warmed
  // No cooling source without expansion; conduction rates interpolated from the grid ([XLS21] eq.
  // (62)) leave an ambient particle next to a heated node within a fraction of a millikelvin
  // (measured −1.6e-4 K against a contact that warms by hundreds of kelvin).
  EXPECT_GE(*std::min_element(T.begin(), T.end()), 293.15 - 1e-3);
}

TEST(DiskSquish, VerifyCaseIsRegistered) {
  const auto& cases = fp::verify_cases();
  EXPECT_TRUE(std::any_of(cases.begin(), cases.end(),
                          [](const auto& c) { return c.name == "disk-squish"; }));
}

// scenes/stability/hot-interface.toml: a face heated past θ_dam stops friction (μ = 0), heat =
// friction work + flux input, nothing blows up.
TEST(HotInterface, StabilityScenePassesItsChecks) {
  const fp::StabilityResult result = fp::run_stability_scene("hot-interface");
  std::string lines;
  for (const auto& line : result.checks) lines += line + "\n";
  EXPECT_TRUE(result.passed) << lines;
  EXPECT_GE(result.checks.size(), 8u) << lines;
  EXPECT_THROW(fp::run_stability_scene("no-such-scene"), std::invalid_argument);
}
