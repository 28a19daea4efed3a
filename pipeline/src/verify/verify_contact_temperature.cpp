// V3: contact-face temperatures across a pressed interface (docs/verification.md; [XLS21] §4.2, eq.
// (90)). Steady conduction through two blocks of length l with a contact conductance h_c between
// them, the outer faces at θ_hot and θ_cool: with κ̄ = h_c l / κ the faces of the interface sit at
//   θ₁ = ((1 + κ̄) θ_hot + κ̄ θ_cool) / (1 + 2κ̄)  (upper block),
//   θ₂ = ((1 + κ̄) θ_cool + κ̄ θ_hot) / (1 + 2κ̄)  (lower block).
// The simulated face temperature of each block is its field's nodal temperature at the interface.
#include <algorithm>
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

/// Temperature of `body`'s field at the interface nodes: the capacity-weighted projection
/// Σ S̄_ip m_p θ_p / Σ S̄_ip m_p onto the node row y = l ([XLS21] Alg. 2 line 19), which is what the
/// solver's heat equation holds there. Along y the CPDI weight of an undeformed, axis-aligned
/// particle domain [y_p − a/2, y_p + a/2] is the mean of the hat over it; the problem is uniform in
/// x. (The particles' own values carry the grid-invisible remnant of eq. (62) updates, see
/// verify_conduction.cpp, and are not the field the equation solves for.)
double face_temperature(const mpm::Particles<2>& P, int body, double cell_size) {
  auto hat_mean = [&](double lo, double hi) {  // mean over [lo, hi] of max(0, 1 − |y − l|/h)
    auto integral = [&](double y) {            // ∫_{l−h}^{y} hat
      const double t = std::clamp((y - block) / cell_size, -1.0, 1.0);
      return cell_size *
             (t <= 0.0 ? 0.5 * (1.0 + t) * (1.0 + t) : 1.0 - 0.5 * (1.0 - t) * (1.0 - t));
    };
    return (integral(hi) - integral(lo)) / (hi - lo);
  };
  double weight = 0.0, heat = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p) {
    if (P.body[p] != body) continue;
    const double half = 0.5 * (std::abs(P.domain[p](1, 0)) + std::abs(P.domain[p](1, 1)));
    const double w = hat_mean(P.x[p][1] - half, P.x[p][1] + half) * P.mass[p];
    weight += w;
    heat += w * P.temperature[p];
  }
  return heat / weight;
}

std::vector<VerifyRow> run_level(double kappa_bar, int level, double cell_size) {
  const std::string text =
      with_overrides(embedded_scene("verify/contact-temperature.toml"),
                     {{"grid.cell_size", toml_number(cell_size)}, {"output.interval", "0.0"}});
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/contact-temperature.toml");
  const double kappa = problem.thermal.materials.at(0).conductivity;
  const double gamma =
      problem.thermal.contact_conductance / problem.thermal.contact_pressure;  // γ̄ (eq. (13))
  const double pressure = kappa_bar * kappa / (block * gamma);  // h_c = γ̄ p = κ̄ κ / l
  problem.loads.at(0).tractions.at(0) = mpm::Vec<2>(0.0, -pressure);
  const double end_time = problem.stop.end_time;
  mpm::Solver<2> solver(std::move(problem));
  const TimedRun run =
      run_until(solver, end_time, "contact-temperature", end_time, [](const mpm::Solver<2>&) {});
  const double upper = face_temperature(solver.particles(), 1, cell_size);
  const double lower = face_temperature(solver.particles(), 0, cell_size);
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
  const std::vector<double> cells =
      options.quick ? std::vector<double>{5e-4} : std::vector<double>{5e-4, 2.5e-4};
  std::vector<VerifyRow> rows;
  for (double kappa_bar : {0.1, 1.0, 10.0})
    for (std::size_t l = 0; l < cells.size(); ++l)
      for (VerifyRow& r : run_level(kappa_bar, static_cast<int>(l), cells[l]))
        rows.push_back(std::move(r));
  return rows;
}

}  // namespace fragmpm::pipeline
