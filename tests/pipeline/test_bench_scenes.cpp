// The peer scenes of `fragmpm bench` compile to the problems other MPM codes run: the stated
// particle counts, masses, momenta, walls, friction and fixed steps below the stability limit.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <variant>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"

namespace fp = fragmpm::pipeline;
namespace mpm = fragmpm::mpm;

namespace {

mpm::Problem<2> embedded(const std::string& name) {
  return fp::parse_scene(fp::embedded_scene(name), "scenes/" + name);
}

double total_mass(const mpm::Problem<2>& p) {
  double m = 0.0;
  for (double x : p.particles.mass) m += x;
  return m;
}

mpm::Vec<2> total_momentum(const mpm::Problem<2>& p) {
  mpm::Vec<2> sum = mpm::Vec<2>::Zero();
  for (std::size_t i = 0; i < p.particles.size(); ++i)
    sum += p.particles.mass[i] * p.particles.v[i];
  return sum;
}

bool module_on(const mpm::Problem<2>& p, const std::string& name) {
  for (const auto& m : mpm::plan_modules<2>(p))
    if (m.module == name) return m.active;
  return false;
}

}  // namespace

TEST(BenchScenes, BlockIs100000ParticlesAt10MetresPerSecondOnARollerWall) {
  const mpm::Problem<2> p = embedded("bench/block.toml");
  ASSERT_EQ(p.particles.size(), 100000u);  // 125 × 200 mm at h = 1 mm, 2 × 2 per cell
  EXPECT_NEAR(total_mass(p), 2300.0 * 0.125 * 0.200, 1e-9 * 57.5);  // kg per unit thickness
  const mpm::Vec<2> momentum = total_momentum(p);
  EXPECT_NEAR(momentum[0], -10.0 * 57.5, 1e-9 * 575.0);
  EXPECT_EQ(momentum[1], 0.0);
  ASSERT_EQ(p.walls.size(), 1u);
  EXPECT_EQ(p.walls[0].kind, mpm::WallKind::roller);
  EXPECT_EQ(p.walls[0].point[0], 0.0);
  double leftmost = 1.0;
  for (const auto& x : p.particles.x) leftmost = std::min(leftmost, x[0]);
  EXPECT_NEAR(leftmost, 0.25e-3, 1e-12);  // the first particle row touches the wall plane
  EXPECT_FALSE(module_on(p, "partitioning"));
  // Fixed Δt = 0.1017 µs, 295 steps: 71 % of the stability limit h / (√2 (c + |v|)).
  EXPECT_DOUBLE_EQ(p.time.fixed_dt, 0.1017e-6);
  EXPECT_EQ(p.stop.max_steps, 295);
  const double limit = mpm::stable_time_step<2>(p, p.particles, 1.0);
  EXPECT_NEAR(p.time.fixed_dt / limit, 0.71, 0.01);
}

TEST(BenchScenes, DisksAreTwoMirrorBodiesOf25974ParticlesWithCoulombContact) {
  const mpm::Problem<2> p = embedded("bench/disks.toml");
  ASSERT_EQ(p.particles.size(), 51948u);
  std::size_t left = 0;
  double left_max_x = -1.0, right_min_x = 1.0;
  for (std::size_t i = 0; i < p.particles.size(); ++i) {
    if (p.particles.body[i] == 0) {
      ++left;
      left_max_x = std::max(left_max_x, p.particles.x[i][0]);
    } else {
      right_min_x = std::min(right_min_x, p.particles.x[i][0]);
    }
  }
  EXPECT_EQ(left, 25974u);  // the two disks are mirror images: the same count each
  // They touch at x = 0: the nearest particles sit half a particle spacing (27.5 µm) either side.
  EXPECT_NEAR(left_max_x, -27.5e-6, 1e-12);
  EXPECT_NEAR(right_min_x, 27.5e-6, 1e-12);
  const mpm::Vec<2> momentum = total_momentum(p);
  EXPECT_NEAR(momentum.norm(), 0.0, 1e-9 * total_mass(p) * 10.0);  // ±10 m/s
  ASSERT_TRUE(std::holds_alternative<mpm::CoulombFriction>(p.contact.friction));
  EXPECT_DOUBLE_EQ(std::get<mpm::CoulombFriction>(p.contact.friction).coefficient, 0.2);
  EXPECT_TRUE(module_on(p, "partitioning"));
  EXPECT_DOUBLE_EQ(p.time.fixed_dt, 0.01119e-6);
  EXPECT_EQ(p.stop.max_steps, 358);
  const double limit = mpm::stable_time_step<2>(p, p.particles, 1.0);
  EXPECT_NEAR(p.time.fixed_dt / limit, 0.71, 0.01);
}

TEST(BenchScenes, BrazilianDiskAtItsPaperCellIs15442Particles) {
  const mpm::Problem<2> p = embedded("paper/brazilian.toml");
  ASSERT_EQ(p.particles.size(), 15442u);
  std::size_t per_body[3] = {0, 0, 0};
  for (int b : p.particles.body) ++per_body[b];
  EXPECT_EQ(per_body[0], 9590u);  // the Ø10 mm disk at h = 0.181 mm, 2 × 2 per cell: π (5 mm)² /
                                  // (0.0905 mm)² = 9,590.3
  EXPECT_EQ(per_body[1], 2926u);  // each 12 × 2 mm platen
  EXPECT_EQ(per_body[2], 2926u);
  EXPECT_DOUBLE_EQ(p.stop.end_time, 20e-6);
  EXPECT_TRUE(module_on(p, "damage"));
  EXPECT_TRUE(module_on(p, "partitioning"));
  // Weibull volumes V = s² t with the 2 mm thickness of [HH17] Table IV: the median strength of the
  // disk's draws is σ̄ (V̄/V)^(1/m) = 140 MPa × (8 cm³ / ((0.0905 mm)² × 2 mm))^(1/6) = 1.242 GPa.
  EXPECT_DOUBLE_EQ(p.materials[0].weibull_strength.thickness, 2e-3);
  std::vector<double> disk;
  for (std::size_t k = 0; k < p.particles.size(); ++k)
    if (p.particles.body[k] == 0) disk.push_back(p.particles.strength[k]);
  std::nth_element(disk.begin(), disk.begin() + disk.size() / 2, disk.end());
  const double s = 0.181e-3 / 2, median = 140e6 * std::pow(8e-6 / (s * s * 2e-3), 1.0 / 6.0);
  EXPECT_NEAR(median, 1.242e9, 0.001e9);
  // 9590 draws: the sample median lies within 1 % of the distribution's.
  EXPECT_NEAR(disk[disk.size() / 2] / median, 1.0, 0.01);
}

TEST(BenchScenes, DamageBlockTakesEachLawAndPassesThePhaseFieldPeak) {
  // The weak material of the damage-law comparison: 10 000 particles at the file's 2 mm cell, on
  // quadratic B-splines. With l₀ = 1 mm and G_c = 1 J/m² the homogeneous AT2 peak stress
  // (9/16) √(E G_c / (6 l₀)) is 1.62 MPa, a little above the 1 MPa strength of the other laws.
  const std::string text = fp::embedded_scene("bench/damage-block.toml");
  const mpm::Problem<2> none = fp::parse_scene(text, "damage-block.toml");
  ASSERT_EQ(none.particles.size(), 10000u);
  EXPECT_EQ(none.grid.shape_function, mpm::ShapeFunctionKind::bspline2);
  EXPECT_FALSE(module_on(none, "damage"));
  const mpm::Problem<2> phase_field =
      fp::parse_scene(fp::with_overrides(text, {{"grid.cell_size", "\"1 mm\""},  // l₀ ≥ h
                                                {"materials[0].damage", "\"phase-field\""},
                                                {"materials[0].length_scale", "\"1 mm\""},
                                                {"materials[0].fracture_energy", "\"1 J/m2\""}}),
                      "damage-block.toml");
  const auto& m = phase_field.materials[0];
  const auto& law = std::get<mpm::PhaseField>(m.damage);
  const double E =
      9.0 * m.bulk_modulus * m.shear_modulus / (3.0 * m.bulk_modulus + m.shear_modulus);
  EXPECT_NEAR(E, 50e9, 1e-3);
  EXPECT_NEAR(9.0 / 16.0 * std::sqrt(E * law.fracture_energy / (6.0 * law.length_scale)), 1.624e6,
              0.001e6);
}
