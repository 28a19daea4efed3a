// V3: contact-face temperatures across a pressed interface (BENCHMARKS.md; 000 §4.2, eq. 90).
// Steady conduction through two blocks of length l with a contact conductance h_c between them,
// the outer faces at θ_hot and θ_cool: with κ̄ = h_c l / κ the faces of the interface sit at
//   θ₁ = ((1 + κ̄) θ_hot + κ̄ θ_cool) / (1 + 2κ̄)  (upper block),
//   θ₂ = ((1 + κ̄) θ_cool + κ̄ θ_hot) / (1 + 2κ̄)  (lower block).
// The simulated face temperature of each block is its particles' least-squares line θ(y) taken at
// the interface y = l (each block is linear at steady state).
#include <cmath>
#include <cstdio>
#include <string>
#include <tuple>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double block = 2.5e-3;  // l [m], as in scenes/verify/contact-temperature.toml
constexpr double hot = 323.15, cool = 293.15;  // [K]

/// θ(y = l) of the least-squares line through the particles of `body`.
double face_temperature(const mpm::Particles<2>& P, int body) {
  double n = 0, sy = 0, st = 0, syy = 0, syt = 0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.body[p] != body) continue;
    const double y = P.x[p][1], t = P.temperature[p];
    n += 1;
    sy += y;
    st += t;
    syy += y * y;
    syt += y * t;
  }
  const double slope = (n * syt - sy * st) / (n * syy - sy * sy);
  return (st - slope * sy) / n + slope * block;
}

std::vector<VerifyRow> run_level(double kappa_bar, int level, double cell_size) {
  const std::string text =
      with_overrides(embedded_scene("verify/contact-temperature.toml"),
                     {{"grid.cell_size", toml_number(cell_size)}, {"output.interval", "0.0"}});
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/contact-temperature.toml");
  const double kappa = problem.thermal.materials.at(0).conductivity;
  const double gamma = problem.thermal.contact_conductance / problem.thermal.contact_pressure;  // γ̄ (eq. 13)
  const double pressure = kappa_bar * kappa / (block * gamma);  // h_c = γ̄ p = κ̄ κ / l
  problem.loads.at(0).tractions.at(0) = mpm::Vec<2>(0.0, -pressure);
  const double end_time = problem.stop.end_time;
  mpm::Solver<2> solver(std::move(problem));
  const TimedRun run = run_until(solver, end_time, "contact-temperature", end_time, [](const mpm::Solver<2>&) {});
  const double upper = face_temperature(solver.particles(), 1), lower = face_temperature(solver.particles(), 0);
  const double theta1 = ((1.0 + kappa_bar) * hot + kappa_bar * cool) / (1.0 + 2.0 * kappa_bar);
  const double theta2 = ((1.0 + kappa_bar) * cool + kappa_bar * hot) / (1.0 + 2.0 * kappa_bar);
  char variant[32];
  std::snprintf(variant, sizeof variant, "kappa-%g", kappa_bar);
  std::vector<VerifyRow> rows;
  for (const auto& [metric, value, reference] :
       {std::tuple{"theta1_upper_face_K (abs error K)", upper, theta1},
        std::tuple{"theta2_lower_face_K (abs error K)", lower, theta2}}) {
    VerifyRow r = level_row("contact-temperature", variant, level, cell_size, solver, run);
    r.metric = metric;
    r.value = value;
    r.reference = reference;
    r.error = std::abs(value - reference);
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_contact_temperature(const VerifyOptions& options) {
  const std::vector<double> cells = options.quick ? std::vector<double>{5e-4} : std::vector<double>{5e-4, 2.5e-4};
  std::vector<VerifyRow> rows;
  for (double kappa_bar : {0.1, 1.0, 10.0})
    for (std::size_t l = 0; l < cells.size(); ++l)
      for (VerifyRow& r : run_level(kappa_bar, static_cast<int>(l), cells[l])) rows.push_back(std::move(r));
  return rows;
}

}  // namespace fragmpm::pipeline
