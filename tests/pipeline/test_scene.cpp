// Scene files: good scenes give exact lattice counts, areas and masses; every malformed scene gives
// a SceneError naming file, line and key.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/scene_shapes.hpp"

namespace fp = fragmpm::pipeline;
namespace mpm = fragmpm::mpm;

namespace {

// A valid scene; bad scenes replace one piece of it. Grid spacing h = 0.5 mm, 2 particles per cell
// per direction: particle spacing s = 0.25 mm, lattice x = (i + 1/2) s.
const std::string kGood = R"(# test scene
[grid]
cell_size = "0.5 mm"
min = ["0 mm", "0 mm"]
max = ["20 mm", "20 mm"]

[time]
cfl = 0.5

[physics]
gravity = ["0 m/s2", "-9.81 m/s2"]

[[materials]]
name = "glass"
E = "70 GPa"
nu = 0.22
density = "2.3 g/cm3"

[[bodies]]
name = "block"
material = "glass"
shape = "box"
min = ["2 mm", "2 mm"]
max = ["6 mm", "4 mm"]

[[walls]]
name = "floor"
point = ["0 mm", "1 mm"]
normal = [0, 2]
friction = 0.2

[stop]
end_time = "250 us"
)";

std::string replace(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "test setup: '" << from << "' not in scene";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

/// 1-based number of the first line of `text` that contains `marker`.
int line_of(const std::string& text, const std::string& marker) {
  const auto at = text.find(marker);
  EXPECT_NE(at, std::string::npos) << "test setup: marker '" << marker << "' not in scene";
  return 1 + static_cast<int>(
                 std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(at), '\n'));
}

/// Parses a scene that must fail; checks file:line, key and a piece of the explanation.
void expect_scene_error(const std::string& text, const std::string& line_marker,
                        const std::string& key, const std::string& explanation) {
  const int line = line_of(text, line_marker);
  try {
    fp::parse_scene(text, "bad.toml");
    ADD_FAILURE() << "no error; expected key '" << key << "' at line " << line;
  } catch (const fp::SceneError& e) {
    const std::string what = e.what();
    EXPECT_EQ(e.file, "bad.toml");
    EXPECT_EQ(e.line, line) << what;
    EXPECT_EQ(e.key, key) << what;
    EXPECT_NE(what.find("bad.toml:" + std::to_string(line) + ": "), std::string::npos) << what;
    if (!key.empty()) {
      EXPECT_NE(what.find("key '" + key + "'"), std::string::npos) << what;
    }
    EXPECT_NE(what.find(explanation), std::string::npos) << what;
  }
}

std::size_t count_body(const mpm::Particles<2>& P, int body) {
  return static_cast<std::size_t>(std::count(P.body.begin(), P.body.end(), body));
}

}  // namespace

// ---------------------------------------------------------------- good scenes

TEST(Scene, OutsidePolicyDefaultsToStop) {
  EXPECT_EQ(fp::parse_scene(kGood, "good.toml").grid.outside, mpm::OutsidePolicy::stop);
  const std::string removing = replace(kGood, "max = [\"20 mm\", \"20 mm\"]",
                                       "max = [\"20 mm\", \"20 mm\"]\noutside = \"remove\"");
  EXPECT_EQ(fp::parse_scene(removing, "good.toml").grid.outside, mpm::OutsidePolicy::remove);
}

TEST(Scene, ShapeFunctionNamesSelectTheirKinds) {
  const std::pair<const char*, mpm::ShapeFunctionKind> kinds[] = {
      {"cpdi", mpm::ShapeFunctionKind::cpdi},
      {"linear", mpm::ShapeFunctionKind::linear},
      {"ugimp", mpm::ShapeFunctionKind::ugimp},
      {"bspline2", mpm::ShapeFunctionKind::bspline2}};
  for (const auto& [name, kind] : kinds) {
    const std::string text =
        replace(kGood, "max = [\"20 mm\", \"20 mm\"]",
                "max = [\"20 mm\", \"20 mm\"]\nshape_function = \"" + std::string(name) + "\"");
    const mpm::Problem<2> p = fp::parse_scene(text, "good.toml");
    EXPECT_EQ(p.grid.shape_function, kind) << name;
    EXPECT_EQ(p.particles.size(), 128u) << name;  // the kernel does not change the sampling
  }
  // The module plan names the kernel the step runs.
  const std::string bspline =
      replace(kGood, "max = [\"20 mm\", \"20 mm\"]",
              "max = [\"20 mm\", \"20 mm\"]\nshape_function = \"bspline2\"");
  const auto plan = mpm::plan_modules<2>(fp::parse_scene(bspline, "good.toml"));
  EXPECT_NE(plan.front().reason.find("quadratic B-spline"), std::string::npos)
      << plan.front().reason;
}

TEST(Scene, BoxGivesTheExactLatticeCountAndUnitsAreSI) {
  const mpm::Problem<2> p = fp::parse_scene(kGood, "good.toml");
  // Box 4 mm x 2 mm at spacing 0.25 mm: 16 x 8 lattice points.
  ASSERT_EQ(p.particles.size(), 128u);
  EXPECT_EQ(p.scene_path, "good.toml");
  EXPECT_EQ(p.scene_text, kGood);
  ASSERT_EQ(p.body_names, std::vector<std::string>{"block"});
  EXPECT_DOUBLE_EQ(p.grid.cell_size, 5e-4);
  EXPECT_EQ(p.grid.shape_function, mpm::ShapeFunctionKind::cpdi);
  EXPECT_DOUBLE_EQ(p.time.cfl, 0.5);
  EXPECT_EQ(p.time.fixed_dt, 0.0);
  EXPECT_EQ(p.time.pic_fraction, 0.0);
  EXPECT_DOUBLE_EQ(p.gravity.y(), -9.81);
  ASSERT_EQ(p.materials.size(), 1u);
  EXPECT_DOUBLE_EQ(p.materials[0].density, 2300.0);                            // "2.3 g/cm3"
  EXPECT_NEAR(p.materials[0].bulk_modulus, 70e9 / (3 * (1 - 2 * 0.22)), 1.0);  // K = E / 3(1 − 2ν)
  EXPECT_NEAR(p.materials[0].shear_modulus, 70e9 / (2 * (1 + 0.22)), 1.0);     // G = E / 2(1 + ν)
  EXPECT_DOUBLE_EQ(p.stop.end_time, 2.5e-4);                                   // "250 us"
  EXPECT_EQ(p.stop.platen, -1);
  EXPECT_DOUBLE_EQ(p.output.interval, 2.5e-4 / 20);  // default end_time / 20
  EXPECT_TRUE(p.output.fields.empty());
  ASSERT_EQ(p.walls.size(), 1u);
  EXPECT_DOUBLE_EQ(p.walls[0].normal.y(), 1.0);  // [0, 2] normalised
  EXPECT_DOUBLE_EQ(p.walls[0].point.y(), 1e-3);
  EXPECT_EQ(p.walls[0].kind, mpm::WallKind::contact);
  EXPECT_DOUBLE_EQ(std::get<mpm::CoulombFriction>(p.walls[0].friction).coefficient, 0.2);
  EXPECT_EQ(p.walls[0].velocity.kind, mpm::HistoryKind::constant);

  const double s = 2.5e-4;
  for (std::size_t k = 0; k < p.particles.size(); ++k) {
    EXPECT_DOUBLE_EQ(p.particles.volume0[k], s * s);
    EXPECT_DOUBLE_EQ(p.particles.mass[k], 2300.0 * s * s);
    EXPECT_TRUE(p.particles.domain[k].isApprox(s * mpm::Mat<2>::Identity()));
    EXPECT_TRUE(p.particles.F[k].isIdentity());
    EXPECT_EQ(p.particles.stress[k].norm(), 0.0);
    EXPECT_EQ(p.particles.damage[k], 0.0);
    EXPECT_TRUE(std::isinf(p.particles.strength[k]));
    EXPECT_EQ(p.particles.v[k].norm(), 0.0);
    // Lattice points x = (i + 1/2) s, all inside the box.
    const double i = p.particles.x[k].x() / s - 0.5, j = p.particles.x[k].y() / s - 0.5;
    EXPECT_NEAR(i, std::round(i), 1e-9);
    EXPECT_NEAR(j, std::round(j), 1e-9);
    EXPECT_GT(p.particles.x[k].x(), 2e-3);
    EXPECT_LT(p.particles.x[k].x(), 6e-3);
    EXPECT_GT(p.particles.x[k].y(), 2e-3);
    EXPECT_LT(p.particles.x[k].y(), 4e-3);
  }
}

TEST(Scene, SurfaceFlagsOnlyOnTheBoundaryOfABox) {
  const mpm::Problem<2> p = fp::parse_scene(kGood, "good.toml");
  const double s = 2.5e-4;
  std::size_t surface = 0;
  for (std::size_t k = 0; k < p.particles.size(); ++k) {
    const Eigen::Vector2d x = p.particles.x[k];
    // Outermost ring of the 16 x 8 lattice: within one spacing of the box edges.
    const bool ring = x.x() < 2e-3 + s || x.x() > 6e-3 - s || x.y() < 2e-3 + s || x.y() > 4e-3 - s;
    EXPECT_EQ(p.particles.surface[k], ring ? 1 : 0) << "particle at " << x.transpose();
    surface += p.particles.surface[k];
  }
  EXPECT_EQ(surface, 128u - 14u * 6u);
}

TEST(Scene, FacesOnRollerWallsAreSymmetryPlanesNotSurfaces) {
  // The block [2, 6] x [2, 4] mm with a roller wall on its left face x = 2 mm (normal +x) and a
  // fixed wall on its bottom face y = 2 mm: the left column lies on a mirror plane (the body
  // continues across it) and loses its flags, except where another face also bounds it; the
  // bottom row on the no-slip wall keeps them.
  const std::string text = replace(kGood, "[[walls]]", R"([[walls]]
name = "mirror"
point = ["2 mm", "0 mm"]
normal = [1, 0]
kind = "roller"

[[walls]]
name = "base"
point = ["0 mm", "2 mm"]
normal = [0, 1]
kind = "fixed"

[[walls]])");
  const mpm::Problem<2> p = fp::parse_scene(text, "mirror.toml");
  const double s = 2.5e-4;
  std::size_t surface = 0;
  for (std::size_t k = 0; k < p.particles.size(); ++k) {
    const Eigen::Vector2d x = p.particles.x[k];
    const bool ring = x.x() > 6e-3 - s || x.y() < 2e-3 + s || x.y() > 4e-3 - s;
    EXPECT_EQ(p.particles.surface[k], ring ? 1 : 0) << "particle at " << x.transpose();
    surface += p.particles.surface[k];
  }
  // 16 x 8 lattice: the top and bottom rows (2 x 16) and the right column's 6 inner particles.
  EXPECT_EQ(surface, 2u * 16u + 6u);
}

namespace {
// kGood with its block's box replaced by the lines of another shape.
std::string with_shape(const std::string& shape) {
  return replace(kGood, "shape = \"box\"\nmin = [\"2 mm\", \"2 mm\"]\nmax = [\"6 mm\", \"4 mm\"]",
                 shape);
}
}  // namespace

TEST(Scene, DiskAreaMassAndSurface) {
  const std::string text = with_shape(R"(shape = "disk"
center = ["10 mm", "10 mm"]
radius = "4 mm")");
  const mpm::Problem<2> p = fp::parse_scene(text, "disk.toml");
  const double r = 4e-3, s = 2.5e-4, rho = 2300.0;
  double area = 0.0, mass = 0.0;
  for (std::size_t k = 0; k < p.particles.size(); ++k) {
    area += p.particles.volume0[k];
    mass += p.particles.mass[k];
    const double depth = r - (p.particles.x[k] - Eigen::Vector2d(10e-3, 10e-3)).norm();
    EXPECT_GE(depth, 0.0);
    // A surface particle has a neighbour (at most √2 s away) outside the disk.
    if (p.particles.surface[k]) {
      EXPECT_LT(depth, std::sqrt(2.0) * s);
    }
    // A particle deeper than √2 s has all eight neighbours inside.
    if (depth >= std::sqrt(2.0) * s) {
      EXPECT_EQ(p.particles.surface[k], 0);
    }
  }
  EXPECT_NEAR(area, std::numbers::pi * r * r, 0.02 * std::numbers::pi * r * r);
  EXPECT_NEAR(mass, rho * area, 1e-12 * mass);
  EXPECT_NEAR(mass, rho * std::numbers::pi * r * r, 0.02 * rho * std::numbers::pi * r * r);
}

// A ring (a disk with inner_radius): its particles lie between the two circles, its area is
// π(R² − r²) to the lattice's resolution, and the hole's rim is a surface like the outer one.
TEST(Scene, RingAreaAndBothRimsAreSurfaces) {
  const std::string text = with_shape(R"(shape = "disk"
center = ["10 mm", "10 mm"]
radius = "6 mm"
inner_radius = "4 mm")");
  const mpm::Problem<2> p = fp::parse_scene(text, "ring.toml");
  const double outer = 6e-3, inner = 4e-3, s = 2.5e-4;
  double area = 0.0;
  int inner_rim = 0, outer_rim = 0;
  for (std::size_t k = 0; k < p.particles.size(); ++k) {
    area += p.particles.volume0[k];
    const double r = (p.particles.x[k] - Eigen::Vector2d(10e-3, 10e-3)).norm();
    EXPECT_GE(r, inner);
    EXPECT_LE(r, outer);
    const bool near_rim = r - inner < std::sqrt(2.0) * s || outer - r < std::sqrt(2.0) * s;
    if (!near_rim) {
      EXPECT_EQ(p.particles.surface[k], 0);
    }
    if (p.particles.surface[k]) (r < 5e-3 ? inner_rim : outer_rim) += 1;
  }
  const double exact = std::numbers::pi * (outer * outer - inner * inner);
  EXPECT_NEAR(area, exact, 0.02 * exact);
  // Rim lengths 2π r over the spacing s: about 100 and 150 particles.
  EXPECT_GT(inner_rim, 2.0 * std::numbers::pi * inner / s * 0.9);
  EXPECT_GT(outer_rim, 2.0 * std::numbers::pi * outer / s * 0.9);
}

TEST(Scene, InitialRigidMotionAboutTheCentroid) {
  const std::string text = with_shape(R"(shape = "disk"
center = ["10 mm", "10 mm"]
radius = "4 mm"
velocity = ["1 m/s", "-2 m/s"]
angular_velocity = "100 rad/s")");
  const mpm::Problem<2> p = fp::parse_scene(text, "spin.toml");
  const auto& P = p.particles;
  double M = 0.0;
  Eigen::Vector2d momentum = Eigen::Vector2d::Zero(), c = Eigen::Vector2d::Zero();
  for (std::size_t k = 0; k < P.size(); ++k) {
    M += P.mass[k];
    momentum += P.mass[k] * P.v[k];
    c += P.mass[k] * P.x[k];
  }
  c /= M;
  // Rotation about the particles' centroid adds no net momentum: p = M v0.
  EXPECT_NEAR(momentum.x(), M * 1.0, 1e-12 * M);
  EXPECT_NEAR(momentum.y(), M * -2.0, 1e-12 * M);
  // Angular momentum about the centroid: L = ω Σ m |x − c|².
  double L = 0.0, I = 0.0;
  for (std::size_t k = 0; k < P.size(); ++k) {
    const Eigen::Vector2d d = P.x[k] - c;
    L += P.mass[k] * (d.x() * P.v[k].y() - d.y() * P.v[k].x());
    I += P.mass[k] * d.squaredNorm();
  }
  EXPECT_NEAR(L, 100.0 * I, 1e-9 * 100.0 * I);
}

TEST(Scene, TouchingBodiesKeepTheirOwnSurfaces) {
  const std::string text = replace(kGood, "[[walls]]", R"([[bodies]]
name = "right"
material = "glass"
shape = "box"
min = ["6 mm", "2 mm"]
max = ["8 mm", "4 mm"]

[[walls]])");
  const mpm::Problem<2> p = fp::parse_scene(text, "two.toml");
  ASSERT_EQ(p.body_names, (std::vector<std::string>{"block", "right"}));
  EXPECT_EQ(count_body(p.particles, 0), 128u);
  EXPECT_EQ(count_body(p.particles, 1), 64u);  // 8 x 8
  std::size_t surface[2] = {0, 0};
  for (std::size_t k = 0; k < p.particles.size(); ++k)
    surface[p.particles.body[k]] += p.particles.surface[k];
  // The shared edge is a surface on both sides (the neighbour belongs to another body).
  EXPECT_EQ(surface[0], 128u - 14u * 6u);
  EXPECT_EQ(surface[1], 64u - 6u * 6u);
}

TEST(Scene, OverlapGoesToTheFirstBodyWithAWarning) {
  const std::string text = replace(kGood, "[[walls]]", R"([[bodies]]
name = "right"
material = "glass"
shape = "box"
min = ["4 mm", "2 mm"]
max = ["8 mm", "4 mm"]

[[walls]])");
  testing::internal::CaptureStderr();
  const mpm::Problem<2> p = fp::parse_scene(text, "overlap.toml");
  const std::string err = testing::internal::GetCapturedStderr();
  EXPECT_EQ(count_body(p.particles, 0), 128u);
  EXPECT_EQ(count_body(p.particles, 1), 64u);  // only the part right of x = 6 mm
  EXPECT_NE(err.find("overlap.toml:" + std::to_string(line_of(text, "name = \"right\"") - 1) +
                     ": warning"),
            std::string::npos)
      << err;
  EXPECT_NE(err.find("'right' overlaps body 'block' at 64 particle sites"), std::string::npos)
      << err;
}

TEST(Scene, ShapeTouchingTheDomainEdgeIsInside) {
  // 1.2 mm − 1 mm is 0.19999999999999987 mm in floating point: round-off must not count as outside.
  std::string text = replace(kGood, "min = [\"0 mm\", \"0 mm\"]", "min = [\"0.2 mm\", \"0 mm\"]");
  text = replace(text, "[[walls]]", R"([[bodies]]
name = "edge"
material = "glass"
shape = "disk"
center = ["1.2 mm", "10 mm"]
radius = "1 mm"

[[walls]])");
  const mpm::Problem<2> p = fp::parse_scene(text, "edge.toml");
  EXPECT_GT(count_body(p.particles, 1), 0u);
}

TEST(Scene, PolygonsExactAndApproximate) {
  // An L of two lattice-aligned rectangles: exactly 16 x 8 + 8 x 8 points.
  const std::string l_shape = replace(kGood, R"(shape = "box"
min = ["2 mm", "2 mm"]
max = ["6 mm", "4 mm"])",
                                      R"(shape = "polygon"
vertices = [["2 mm", "2 mm"], ["6 mm", "2 mm"], ["6 mm", "4 mm"], ["4 mm", "4 mm"], ["4 mm", "6 mm"], ["2 mm", "6 mm"]])");
  EXPECT_EQ(fp::parse_scene(l_shape, "l.toml").particles.size(), 128u + 64u);
  // A right triangle with legs of a = 8.125 mm on lattice cell edges, clockwise; its hypotenuse
  // x + y = 12.125 mm passes between lattice points (x + y = (i + j + 1) s): area a²/2 within 2%.
  const std::string triangle = replace(kGood, R"(shape = "box"
min = ["2 mm", "2 mm"]
max = ["6 mm", "4 mm"])",
                                       R"(shape = "polygon"
vertices = [[0.002, 0.002], [0.002, 0.010125], [0.010125, 0.002]])");
  const mpm::Problem<2> p = fp::parse_scene(triangle, "tri.toml");
  double area = 0.0;
  for (double v : p.particles.volume0) area += v;
  const double a = 8.125e-3;
  EXPECT_NEAR(area, a * a / 2, 0.02 * a * a / 2);
}

TEST(Scene, WallHistoriesPlatenStopAndOutput) {
  const std::string text = replace(kGood, "[stop]\nend_time = \"250 us\"\n", R"([[walls]]
name = "top"
point = ["0 mm", "19 mm"]
normal = [0, -1]
kind = "fixed"
[walls.velocity]
type = "ramp"
from = ["0 m/s", "0 m/s"]
to = ["0 m/s", "-0.1 m/s"]
t_end = "10 us"

[[walls]]
name = "shaker"
point = ["19 mm", "0 mm"]
normal = [-1, 0]
kind = "roller"
velocity = { type = "sinusoid", amplitude = ["1 mm/s", "0 m/s"], frequency = "1 kHz", phase = "90 deg" }

[[walls]]
name = "driver"
point = ["2 mm", "0 mm"]
normal = [1, 0]
kind = "roller"
region = { min = ["-1 mm", "5 mm"], max = ["2 mm", "15 mm"] }
velocity = { type = "sinusoid", amplitude = ["2 m/s", "0 m/s"], frequency = "250 Hz", t_start = "1 ms" }

[stop]
platen_displacement = "0.5 mm"
platen = "top"
max_steps = 1e5

[output]
interval = "0.1 ms"
fields = ["x", "damage", "stress"]
)");
  const mpm::Problem<2> p = fp::parse_scene(text, "walls.toml");
  ASSERT_EQ(p.walls.size(), 4u);
  const auto& top = p.walls[1];
  EXPECT_EQ(top.kind, mpm::WallKind::fixed);
  EXPECT_EQ(top.velocity.kind, mpm::HistoryKind::ramp);
  EXPECT_DOUBLE_EQ(top.velocity.t_start, 0.0);
  EXPECT_DOUBLE_EQ(top.velocity.t_end, 1e-5);
  EXPECT_DOUBLE_EQ(top.velocity.to.y(), -0.1);
  EXPECT_DOUBLE_EQ(top.normal.y(), -1.0);
  const auto& shaker = p.walls[2];
  EXPECT_EQ(shaker.kind, mpm::WallKind::roller);
  EXPECT_EQ(shaker.velocity.kind, mpm::HistoryKind::sinusoid);
  EXPECT_DOUBLE_EQ(shaker.velocity.amplitude.x(), 1e-3);
  EXPECT_DOUBLE_EQ(shaker.velocity.frequency, 1000.0);
  EXPECT_DOUBLE_EQ(shaker.velocity.phase, std::numbers::pi / 2);
  EXPECT_FALSE(shaker.region.bounded);
  // A delayed sinusoid ([NBS18] eq. (44)): at rest until t_start, then v_max sin ω(t − t1); after
  // half a period it has moved 2 v_max/ω, and a bounded wall acts only inside its (moving) box.
  const auto& driver = p.walls[3];
  EXPECT_DOUBLE_EQ(driver.velocity.t_start, 1e-3);
  EXPECT_DOUBLE_EQ(driver.velocity.velocity(0.9e-3).x(), 0.0);
  EXPECT_DOUBLE_EQ(driver.velocity.displacement(0.9e-3).x(), 0.0);
  EXPECT_NEAR(driver.velocity.velocity(2e-3).x(), 2.0, 1e-12);
  const double omega = 2.0 * std::numbers::pi * 250.0;
  EXPECT_NEAR(driver.velocity.displacement(3e-3).x(), 2.0 * 2.0 / omega, 1e-15);
  ASSERT_TRUE(driver.region.bounded);
  const mpm::Vec<2> shift(1e-3, 0.0);
  EXPECT_TRUE(driver.region.contains(mpm::Vec<2>(2.5e-3, 10e-3), shift, 1e-12));
  EXPECT_FALSE(driver.region.contains(mpm::Vec<2>(3.5e-3, 10e-3), shift, 1e-12));
  EXPECT_FALSE(driver.region.contains(mpm::Vec<2>(2.5e-3, 4e-3), shift, 1e-12));
  EXPECT_EQ(p.stop.platen, 1);
  EXPECT_DOUBLE_EQ(p.stop.platen_displacement, 5e-4);
  EXPECT_EQ(p.stop.max_steps, 100000);
  EXPECT_TRUE(std::isinf(p.stop.end_time));
  EXPECT_DOUBLE_EQ(p.output.interval, 1e-4);
  EXPECT_EQ(p.output.fields, (std::vector<std::string>{"x", "damage", "stress"}));
}

TEST(Scene, FixedTimeStepAcceptedUpToTheHardLimit) {
  // Stability limit at C_cfl = 1 for particles at rest: h / (c √D), c = sqrt((K + 4G/3) / ρ), D = 2
  // (the stiffest grid mode of multilinear hats with a lumped mass has ω = 2c√D/h).
  const double E = 70e9, nu = 0.22, rho = 2300.0, h = 5e-4;
  const double K = E / (3 * (1 - 2 * nu)), G = E / (2 * (1 + nu));
  const double limit = h / (std::sqrt(2.0) * std::sqrt((K + 4.0 * G / 3.0) / rho));
  auto with_dt = [&](double dt) {
    char line[64];
    std::snprintf(line, sizeof line, "cfl = 0.5\ndt = %.17g", dt);
    return replace(kGood, "cfl = 0.5", line);
  };
  // Above cfl * limit but below the limit: allowed (the user asked for it).
  EXPECT_DOUBLE_EQ(fp::parse_scene(with_dt(0.99 * limit), "dt.toml").time.fixed_dt, 0.99 * limit);
  EXPECT_NEAR(mpm::stable_time_step<2>(fp::parse_scene(kGood, "g.toml"),
                                       fp::parse_scene(kGood, "g.toml").particles, 1.0),
              limit, 1e-12 * limit);
  const std::string bad = with_dt(1.01 * limit);
  char expected[160];
  std::snprintf(expected, sizeof expected, "exceeds the stability limit %.6g s (C_cfl = 1)", limit);
  expect_scene_error(bad, "dt = ", "time.dt", expected);
}

TEST(Scene, ShippedDiskBounceLoads) {
  const mpm::Problem<2> p =
      fp::load_scene(std::string(FRAGMPM_SOURCE_DIR) + "/scenes/disk-bounce.toml");
  ASSERT_EQ(p.body_names.size(), 1u);
  double area = 0.0;
  for (double v : p.particles.volume0) area += v;
  const double r = 5e-3;
  EXPECT_NEAR(area, std::numbers::pi * r * r, 0.02 * std::numbers::pi * r * r);
  EXPECT_DOUBLE_EQ(p.materials[0].density, 1000.0);
  EXPECT_DOUBLE_EQ(p.particles.v[0].y(), -5.0);
  EXPECT_DOUBLE_EQ(p.gravity.y(), -9.81);
  ASSERT_FALSE(p.walls.empty());
  EXPECT_EQ(p.walls[0].name, "floor");
  EXPECT_DOUBLE_EQ(std::get<mpm::CoulombFriction>(p.walls[0].friction).coefficient, 0.3);
  EXPECT_DOUBLE_EQ(p.output.interval, 1e-3);
}

TEST(Scene, MissingFileIsASceneErrorWithoutLine) {
  try {
    fp::load_scene("/nonexistent/dir/scene.toml");
    ADD_FAILURE() << "no error";
  } catch (const fp::SceneError& e) {
    EXPECT_EQ(e.line, 0);
    EXPECT_EQ(e.file, "/nonexistent/dir/scene.toml");
    EXPECT_NE(std::string(e.what()).find("/nonexistent/dir/scene.toml: cannot open scene file"),
              std::string::npos)
        << e.what();
  }
}

TEST(SceneShapes, PolygonSimplicity) {
  using V = Eigen::Vector2d;
  EXPECT_EQ(fp::polygon_self_intersection({V(0, 0), V(1, 0), V(1, 1), V(0, 1)}),
            std::make_pair(-1, -1));
  // Bow tie: edges 0 (v0-v1) and 2 (v2-v3) cross.
  EXPECT_EQ(fp::polygon_self_intersection({V(0, 0), V(1, 1), V(1, 0), V(0, 1)}),
            std::make_pair(0, 2));
  // Spike folding back along itself.
  EXPECT_EQ(fp::polygon_self_intersection({V(0, 0), V(2, 0), V(1, 0), V(0, 1)}).first, 0);
  // Repeated vertex.
  EXPECT_EQ(fp::polygon_self_intersection({V(0, 0), V(1, 0), V(1, 0), V(0, 1)}),
            std::make_pair(1, 1));
  EXPECT_DOUBLE_EQ(fp::polygon_area({V(0, 0), V(0, 2), V(3, 2), V(3, 0)}), 6.0);
}

// ---------------------------------------------------------------- bad scenes

struct BadScene {
  const char* name;
  std::string text;
  std::string line_marker;  ///< first line containing this is where the error must point
  std::string key;
  std::string explanation;  ///< a piece of the message
};

/// gtest prints each parameter beside the test name (and CMake's test discovery copies that into
/// the ctest name): the case name instead of a byte dump of the struct.
inline void PrintTo(const BadScene& c, std::ostream* os) {
  *os << c.name;
}

class BadSceneTest : public testing::TestWithParam<BadScene> {};

TEST_P(BadSceneTest, NamesFileLineKeyAndWhatWasExpected) {
  const BadScene& c = GetParam();
  expect_scene_error(c.text, c.line_marker, c.key, c.explanation);
}

namespace {

const std::string kBox = R"(shape = "box"
min = ["2 mm", "2 mm"]
max = ["6 mm", "4 mm"])";

std::string with_second_body(const std::string& body) {
  return replace(kGood, "[[walls]]", "[[bodies]] # second\n" + body + "\n\n[[walls]]");
}

std::vector<BadScene> bad_scenes() {
  return {
      {"unknown_key", replace(kGood, "cfl = 0.5", "cfl = 0.5\ncfl_max = 1"), "cfl_max",
       "time.cfl_max",
       "unknown key: expected one of cfl, dt, transfer, pic_fraction, thermal_pic_fraction"},
      {"unknown_transfer", replace(kGood, "cfl = 0.5", "cfl = 0.5\ntransfer = \"pic\""), "transfer",
       "time.transfer", "one of \"flip\""},
      {"pic_fraction_with_apic",
       replace(kGood, "cfl = 0.5", "cfl = 0.5\ntransfer = \"apic\"\npic_fraction = 0.1"),
       "pic_fraction", "time.pic_fraction", "the FLIP/PIC blend is FLIP's"},
      {"thermal_pic_fraction_above_one",
       replace(kGood, "cfl = 0.5", "cfl = 0.5\nthermal_pic_fraction = 1.5"), "thermal_pic_fraction",
       "time.thermal_pic_fraction", "0 <= thermal_pic_fraction <= 1"},
      {"misspelt_key", replace(kGood, "cell_size =", "cel_size ="), "cel_size", "grid.cel_size",
       "did you mean 'cell_size'"},
      {"unknown_outside_policy",
       replace(kGood, "max = [\"20 mm\", \"20 mm\"]",
               "max = [\"20 mm\", \"20 mm\"]\noutside = \"vanish\""),
       "outside", "grid.outside",
       "expected one of \"stop\" (a particle leaving the domain stops the run) or \"remove\""},
      {"unknown_table", kGood + "\n[solver]\norder = 2\n", "[solver]", "solver", "unknown key"},
      {"missing_key", replace(kGood, "density = \"2.3 g/cm3\"\n", ""), "[[materials]]",
       "materials[0].density", "missing required key: expected a density"},
      {"wrong_unit", replace(kGood, "\"70 GPa\"", "\"5 m\""), "E = ", "materials[0].E",
       "expected a pressure (SI unit Pa, e.g. \"50 GPa\"), got \"5 m\", which is a length"},
      {"unparseable_quantity", replace(kGood, "\"70 GPa\"", "\"seventy GPa\""),
       "E = ", "materials[0].E", "does not start with a number"},
      {"unknown_unit", replace(kGood, "\"0.5 mm\"", "\"0.5 furlong\""), "cell_size",
       "grid.cell_size", "unknown unit 'furlong'"},
      {"nu_incompressible", replace(kGood, "nu = 0.22", "nu = 0.5"), "nu = ", "materials[0].nu",
       "expected a Poisson's ratio -1 < nu < 0.5, got 0.5"},
      {"nu_below_minus_one", replace(kGood, "nu = 0.22", "nu = -1"), "nu = ", "materials[0].nu",
       "got -1"},
      {"negative_modulus", replace(kGood, "\"70 GPa\"", "\"-70 GPa\""), "E = ", "materials[0].E",
       "expected a positive Young's modulus, got \"-70 GPa\""},
      {"negative_bulk_modulus",
       replace(kGood, "E = \"70 GPa\"\nnu = 0.22", "K = \"-1 GPa\"\nG = \"1 GPa\""),
       "K = ", "materials[0].K", "positive bulk modulus"},
      {"both_elastic_pairs", replace(kGood, "nu = 0.22", "nu = 0.22\nG = \"1 GPa\""),
       "G = ", "materials[0].G", "either (E, nu) or (K, G)"},
      {"zero_density", replace(kGood, "\"2.3 g/cm3\"", "0"), "density", "materials[0].density",
       "positive density"},
      {"unknown_model", replace(kGood, "name = \"glass\"", "name = \"glass\"\nmodel = \"mooney\""),
       "mooney", "materials[0].model", "neo-hookean"},
      {"unknown_material", replace(kGood, "material = \"glass\"", "material = \"steel\""),
       "material = ", "bodies[0].material",
       "expected the name of a material defined in [[materials]] (\"glass\")"},
      {"duplicate_body",
       with_second_body("name = \"block\" # again\nmaterial = \"glass\"\n" + kBox), "# again",
       "bodies[1].name",
       "already defined at line " + std::to_string(line_of(kGood, "name = \"block\""))},
      {"duplicate_material",
       replace(kGood, "[[bodies]]",
               "[[materials]]\nname = \"glass\" # twice\nK = 1\nG = 1\ndensity = 1\n\n[[bodies]]"),
       "# twice", "materials[1].name", "already defined"},
      {"empty_body", with_second_body(R"(name = "speck"
material = "glass"
shape = "disk"
center = ["10 mm", "10 mm"]
radius = "0.05 mm")"),
       "0.05 mm", "bodies[1].radius", "smaller than the particle spacing h/n = 0.00025 m"},
      {"hidden_body",
       with_second_body("name = \"inner\"\nmaterial = \"glass\"\nshape = \"box\"\n"
                        "min = [\"3 mm\", \"2.5 mm\"]\nmax = [\"4 mm\", \"3 mm\"]"),
       "# second", "bodies[1]", "lie inside earlier bodies ('block')"},
      {"box_outside_grid",
       replace(kGood, "max = [\"6 mm\", \"4 mm\"]", "max = [\"21 mm\", \"4 mm\"]"), "21 mm",
       "bodies[0].max", "extends 0.001 m outside it, above grid.max in x"},
      {"disk_outside_grid", with_second_body(R"(name = "ball"
material = "glass"
shape = "disk"
center = ["12 mm", "-2 mm"]
radius = "4 mm")"),
       "-2 mm", "bodies[1].center", "extends 0.006 m outside it, below grid.min in y"},
      {"zero_cell_size", replace(kGood, "\"0.5 mm\"", "\"0 mm\""), "cell_size", "grid.cell_size",
       "expected a positive length, got \"0 mm\""},
      {"cell_larger_than_domain", replace(kGood, "\"0.5 mm\"", "\"30 mm\""), "cell_size",
       "grid.cell_size", "no larger than the domain (0.02 m x 0.02 m)"},
      {"max_not_above_min",
       replace(kGood, "max = [\"20 mm\", \"20 mm\"]", "max = [\"20 mm\", \"0 mm\"]"),
       "max = [\"20 mm\", \"0 mm\"]", "grid.max", "expected max > min"},
      {"vector_wrong_length", replace(kGood, "min = [\"0 mm\", \"0 mm\"]", "min = [\"0 mm\"]"),
       "min = [\"0 mm\"]", "grid.min", "expected an array of 2 components"},
      {"wrong_unit_in_vector", replace(kGood, "\"-9.81 m/s2\"", "\"-9.81 m/s\""), "gravity",
       "physics.gravity[1]", "expected an acceleration"},
      {"unknown_shape_function",
       replace(kGood, "max = [\"20 mm\", \"20 mm\"]",
               "max = [\"20 mm\", \"20 mm\"]\nshape_function = \"quadratic\""),
       "quadratic", "grid.shape_function", "one of \"cpdi\", \"linear\", \"ugimp\", \"bspline2\""},
      {"particles_per_cell_zero",
       replace(kGood, "max = [\"20 mm\", \"20 mm\"]",
               "max = [\"20 mm\", \"20 mm\"]\nparticles_per_cell = 0"),
       "particles_per_cell", "grid.particles_per_cell", "an integer from 1 to 16"},
      {"unknown_shape", replace(kGood, "shape = \"box\"", "shape = \"circle\""), "circle",
       "bodies[0].shape", "one of \"disk\", \"box\", \"polygon\""},
      {"key_of_other_shape",
       replace(kGood, "shape = \"box\"", "shape = \"box\"\nradius = \"1 mm\""), "radius",
       "bodies[0].radius", "unknown key"},
      {"ring_hole_not_inside", with_second_body(R"(name = "ring"
material = "glass"
shape = "disk"
center = ["12 mm", "12 mm"]
radius = "4 mm"
inner_radius = "4 mm")"),
       "inner_radius", "bodies[1].inner_radius",
       "expected a length from 0 up to the radius 0.004 m (a ring's hole), got 0.004 m"},
      {"self_intersecting_polygon",
       replace(kGood, kBox,
               "shape = \"polygon\"\nvertices = [[0.002, 0.002], [0.004, 0.004], [0.004, 0.002], "
               "[0.002, 0.004]]"),
       "vertices", "bodies[0].vertices",
       "expected a simple polygon, got edges between vertices 0-1 and 2-3"},
      {"unknown_wall_kind", replace(kGood, "friction = 0.2", "kind = \"sticky\""), "sticky",
       "walls[0].kind", "one of \"contact\", \"roller\", \"fixed\""},
      {"zero_normal", replace(kGood, "normal = [0, 2]", "normal = [0, 0.0]"), "normal",
       "walls[0].normal", "expected a non-zero normal vector"},
      {"negative_friction", replace(kGood, "friction = 0.2", "friction = -0.1"), "friction",
       "walls[0].friction", "friction coefficient >= 0, got -0.1"},
      {"friction_on_fixed_wall",
       replace(kGood, "friction = 0.2", "kind = \"fixed\"\nfriction = 0.2"), "friction",
       "walls[0].friction", "contact walls only"},
      {"unknown_velocity_type", replace(kGood, "friction = 0.2", "velocity = { type = \"jerk\" }"),
       "jerk", "walls[0].velocity.type", "one of \"constant\", \"ramp\", \"sinusoid\""},
      {"ramp_ends_before_start",
       replace(kGood, "friction = 0.2",
               "velocity = { type = \"ramp\", from = [0, 0], to = [0, 1], t_start = \"2 ms\", "
               "t_end = \"1 ms\" }"),
       "ramp", "walls[0].velocity.t_end", "t_end > t_start = 0.002 s"},
      {"wall_region_inverted",
       replace(kGood, "friction = 0.2",
               "region = { min = [\"5 mm\", \"0 mm\"], max = [\"1 mm\", \"9 mm\"] }"),
       "region", "walls[0].region.max", "a corner above and to the right of min"},
      {"walls_not_an_array", replace(kGood, "[[walls]]", "[walls]"), "[walls]", "walls",
       "expected at least one [[walls]] table, got a table"},
      {"no_stop_condition", replace(kGood, "end_time = \"250 us\"\n", ""), "[stop]", "stop",
       "no stop condition: expected at least one of end_time, max_steps, platen_displacement"},
      {"missing_stop_table", replace(kGood, "[stop]\nend_time = \"250 us\"\n", ""), "# test scene",
       "stop", "missing required table [stop]"},
      {"platen_unknown_wall",
       replace(kGood, "end_time = \"250 us\"", "platen_displacement = \"1 mm\"\nplaten = \"lid\""),
       "platen = ", "stop.platen", "a wall defined in [[walls]] (\"floor\"), got \"lid\""},
      {"platen_displacement_without_platen",
       replace(kGood, "end_time = \"250 us\"", "platen_displacement = \"1 mm\""), "[stop]",
       "stop.platen", "platen_displacement needs platen"},
      {"platen_never_moves",
       replace(kGood, "end_time = \"250 us\"",
               "platen_displacement = \"1 mm\"\nplaten = \"floor\""),
       "platen = ", "stop.platen", "velocity is zero at all times"},
      {"unknown_output_field", kGood + "[output]\nfields = [\"x\",\n  \"temprature\"]\n",
       "temprature", "output.fields[1]", "got \"temprature\""},
      {"number_expected", replace(kGood, "cfl = 0.5", "cfl = \"fast\""), "cfl", "time.cfl",
       "expected a number, got \"fast\""},
      {"cfl_out_of_range", replace(kGood, "cfl = 0.5", "cfl = 1.5"), "cfl", "time.cfl",
       "0 < cfl <= 1"},
      {"toml_syntax", replace(kGood, "nu = 0.22", "nu = = 0.22"), "nu = =", "",
       "TOML syntax error"},
  };
}

}  // namespace

INSTANTIATE_TEST_SUITE_P(Scene, BadSceneTest, testing::ValuesIn(bad_scenes()),
                         [](const testing::TestParamInfo<BadScene>& info) {
                           return std::string(info.param.name);
                         });
