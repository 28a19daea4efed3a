// V4: one-dimensional heat conduction from a temperature step (BENCHMARKS.md). The strip of
// scenes/verify/conduction.toml starts at θ_left for x < x_step and θ_left + Δθ beyond; the exact
// answer of the infinite slab is
//   θ(x, t) = θ_left + Δθ/2 · erfc(−(x − x_step) / (2 √(a t))),  a = κ / (ρ c).
// Metric: the largest particle error |θ_p − θ(x_p, t)| as a fraction of Δθ, at 1 ms and 4 ms.
#include <cmath>
#include <map>
#include <stdexcept>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double step_position = 0.020;  // x_step [m]
constexpr double temperature_jump = 100.0;  // Δθ [K]
const std::vector<double> comparison_times = {1e-3, 4e-3};  // [s]

std::vector<VerifyRow> run_conduction_level(int level, double cell_size) {
  const std::string text =
      with_overrides(embedded_scene("verify/conduction.toml"),
                     {{"grid.cell_size", toml_number(cell_size)}, {"output.interval", "0.0"}});
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/conduction.toml");
  const mpm::ThermalMaterial& slab = problem.thermal.materials.at(0);
  const double left = problem.particles.temperature.at(0);
  for (std::size_t p = 0; p < problem.particles.size(); ++p)
    if (problem.particles.x[p][0] > step_position) problem.particles.temperature[p] = left + temperature_jump;
  const double diffusivity = slab.conductivity / (problem.materials[0].density * slab.specific_heat);

  mpm::Solver<2> solver(std::move(problem));
  std::map<double, double> worst;  // comparison time -> largest |θ_p − θ| / Δθ
  const TimedRun run = run_until(solver, comparison_times.back(), "conduction", comparison_times.front(),
                                 [&](const mpm::Solver<2>& s) {
                                   for (double t : comparison_times)
                                     if (std::abs(s.time() - t) <= 1e-9 * t) {
                                       const auto& P = s.particles();
                                       const double spread = 2.0 * std::sqrt(diffusivity * s.time());
                                       double e = 0.0;
                                       for (std::size_t p = 0; p < P.size(); ++p) {
                                         const double exact =
                                             left + 0.5 * temperature_jump *
                                                        std::erfc(-(P.x[p][0] - step_position) / spread);
                                         e = std::max(e, std::abs(P.temperature[p] - exact));
                                       }
                                       worst[t] = e / temperature_jump;
                                     }
                                 });
  std::vector<VerifyRow> rows;
  for (double t : comparison_times) {
    if (!worst.count(t)) throw std::runtime_error("conduction: no state at t = " + std::to_string(t) + " s");
    VerifyRow r = level_row("conduction", "cpdi", level, cell_size, solver, run);
    r.metric = "max_error/step_t" + std::to_string(static_cast<int>(std::lround(t * 1e3))) + "ms";
    r.value = worst[t];
    r.reference = 0.0;
    r.error = r.value;
    rows.push_back(r);
  }
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_conduction(const VerifyOptions& options) {
  const std::vector<double> cells = options.quick ? std::vector<double>{1e-3, 5e-4, 2.5e-4}
                                                  : std::vector<double>{1e-3, 5e-4, 2.5e-4, 1.25e-4};
  std::vector<VerifyRow> rows;
  for (std::size_t l = 0; l < cells.size(); ++l)
    for (VerifyRow& r : run_conduction_level(static_cast<int>(l), cells[l])) rows.push_back(std::move(r));
  return rows;
}

}  // namespace fragmpm::pipeline
