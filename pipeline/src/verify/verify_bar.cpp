// V1: axial vibration of an elastic bar (docs/verification.md). Exact solution of the 1D wave
// equation with a fixed end at x = 0 and a free end at x = L in its first mode:
//   v(x, t) = v0 cos(ωt) sin(βx),  β = π/(2L),  ω = β sqrt(E/ρ)   (ν = 0, so plane strain is 1D),
// whose centre-of-mass velocity is v_cm(t) = (1/L)∫ v dx = v0 cos(ωt) · 2/π.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double bar_length = 0.025;  // [m], as in scenes/verify/bar.toml
constexpr double v0 = 1e-3;           // [m/s]: strain amplitude v0/c ≈ 3e-6, small strain

VerifyRow run_bar_level(const std::string& variant, int level, int cells_along_bar) {
  const double cell_size = bar_length / cells_along_bar;
  const std::string text = with_overrides(embedded_scene("verify/bar.toml"),
                                          {{"grid.cell_size", toml_number(cell_size)},
                                           {"grid.shape_function", "\"" + variant + "\""},
                                           {"output.interval", "0.0"}});
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/bar.toml");
  const double E = 9.0 * problem.materials[0].bulk_modulus * problem.materials[0].shear_modulus /
                   (3.0 * problem.materials[0].bulk_modulus + problem.materials[0].shear_modulus);
  const double density = problem.materials[0].density;
  const double beta = std::numbers::pi / (2.0 * bar_length);
  const double omega = beta * std::sqrt(E / density);
  const double period = 2.0 * std::numbers::pi / omega;
  for (std::size_t p = 0; p < problem.particles.size(); ++p)
    problem.particles.v[p] = mpm::Vec<2>(v0 * std::sin(beta * problem.particles.x[p][0]), 0.0);
  double total_mass = 0.0;
  for (double m : problem.particles.mass) total_mass += m;

  mpm::Solver<2> solver(std::move(problem));
  const double amplitude = v0 * 2.0 / std::numbers::pi;
  // RMS over one period by the trapezoidal rule in time (steps are not uniform at the end).
  double squared_integral = 0.0,
         previous_error = solver.last_row().momentum[0] / total_mass - amplitude;
  previous_error *= previous_error;
  double largest_dt = 0.0;  // the last step is shortened to end on the period
  const auto start = std::chrono::steady_clock::now();
  while (solver.time() < period * (1.0 - 1e-12)) {
    if (auto failure = solver.step(period - solver.time()))
      throw std::runtime_error("bar: " + failure->what);
    const auto& row = solver.last_row();
    const double exact = amplitude * std::cos(omega * row.time);
    const double error = row.momentum[0] / total_mass - exact;
    squared_integral += 0.5 * row.dt * (error * error + previous_error);
    previous_error = error * error;
    largest_dt = std::max(largest_dt, row.dt);
  }
  VerifyRow r;
  r.case_name = "bar";
  r.variant = variant;
  r.level = level;
  r.cell_size = cell_size;
  r.particles = static_cast<long long>(solver.particles().size());
  r.dt = largest_dt;
  r.steps = solver.step_count();
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  r.metric = "vcm_rms_error/amplitude";
  r.value = std::sqrt(squared_integral / period) / amplitude;
  r.reference = 0.0;
  r.error = r.value;
  return r;
}

}  // namespace

std::vector<VerifyRow> verify_bar(const VerifyOptions& options) {
  // Cells along the bar: h = L/N must divide 5 mm (scene origin) so a node row lies on x = 0.
  const std::vector<int> levels =
      options.quick ? std::vector<int>{10, 20, 40} : std::vector<int>{10, 20, 40, 80, 160};
  std::vector<VerifyRow> rows;
  for (const std::string variant : {"cpdi", "linear", "bspline2"})
    for (std::size_t l = 0; l < levels.size(); ++l)
      rows.push_back(run_bar_level(variant, static_cast<int>(l), levels[l]));
  return rows;
}

}  // namespace fragmpm::pipeline
