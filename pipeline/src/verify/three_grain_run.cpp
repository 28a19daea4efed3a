// One three-grain crushing run (three_grain_run.hpp): the scene is embedded, its grain file is
// found in the source tree (source_file.hpp) and resolved beside the scene's path there.
#include "three_grain_run.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <stdexcept>
#include <unordered_map>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/source_file.hpp"

namespace fragmpm::pipeline {

namespace {

/// The grain file every three-grain scene reads (`grains = "three-grain-column.h5"` beside it).
constexpr const char* grain_file = "scenes/paper/three-grain-column.h5";

/// Body id of the grain whose particles have the highest mean y: the top of the column.
int highest_body(const mpm::Particles<2>& particles) {
  std::map<int, std::pair<double, double>> sums;  // body → (Σ y, count)
  for (std::size_t p = 0; p < particles.size(); ++p) {
    auto& s = sums[particles.body[p]];
    s.first += particles.x[p][1];
    s.second += 1.0;
  }
  int best = -1;
  double best_y = -std::numeric_limits<double>::infinity();
  for (const auto& [body, s] : sums)
    if (s.first / s.second > best_y) best_y = s.first / s.second, best = body;
  return best;
}

/// The particles of `body` in `current` and, in the same order, their reference states (matched by
/// id: particles that left the domain are gone from `current`).
std::pair<mpm::Particles<2>, mpm::Particles<2>> body_pair(
    const mpm::Particles<2>& reference, const std::unordered_map<std::int32_t, std::size_t>& row_of,
    const mpm::Particles<2>& current, int body) {
  std::vector<std::size_t> now, then;
  for (std::size_t p = 0; p < current.size(); ++p)
    if (current.body[p] == body) {
      now.push_back(p);
      then.push_back(current.id.empty() ? p : row_of.at(current.id[p]));
    }
  return {reference.select(then), current.select(now)};
}

}  // namespace

ThreeGrainRun run_three_grain(const ThreeGrainRunSpec& spec) {
  const std::filesystem::path grains(find_source_file(grain_file, "the three-grain grain file"));
  // Relative paths in the scene resolve against the scene's own folder in the source tree.
  const std::string scene_path =
      (grains.parent_path() / std::filesystem::path(spec.scene).filename()).string();
  char velocity[96];
  std::snprintf(velocity, sizeof velocity,
                "{ type = \"constant\", value = [\"0 m/s\", \"%.17g m/s\"] }", -spec.platen_speed);
  const std::map<std::string, std::string> overrides{
      {"grid.cell_size", toml_number(spec.cell_size)},
      {"walls[3].velocity", velocity},
      {"output.interval", "0.0"}};
  mpm::Problem<2> problem =
      parse_scene(with_overrides(embedded_scene(spec.scene), overrides), scene_path);
  int platen = -1;
  for (std::size_t w = 0; w < problem.walls.size(); ++w)
    if (problem.walls[w].name == "platen") platen = static_cast<int>(w);
  if (platen != 3)
    throw std::runtime_error("three-grain: scene " + spec.scene +
                             " must have the wall 'platen' as its fourth [[walls]] entry");

  ThreeGrainRun run;
  run.spec = spec;
  run.reference = problem.particles;
  run.top_body = highest_body(problem.particles);
  run.particles = static_cast<long long>(problem.particles.size());
  std::unordered_map<std::int32_t, std::size_t> row_of;
  // A particle's id is its index at step 0 (frames keep it when others leave the domain).
  for (std::size_t p = 0; p < run.reference.size(); ++p)
    row_of[run.reference.id.empty() ? static_cast<std::int32_t>(p) : run.reference.id[p]] = p;

  mpm::Solver<2> solver(std::move(problem));
  const auto& T0 = solver.particles().temperature;
  run.thermal = !T0.empty();
  const double initial_hottest = run.thermal ? *std::max_element(T0.begin(), T0.end()) : 0.0;
  double peak_force = 0.0, hottest_rise = 0.0, window_force = 0.0;
  const auto start = std::chrono::steady_clock::now();
  for (double target : spec.displacements) {
    const double target_time = target / spec.platen_speed;  // the platen moves at constant speed
    while (solver.time() < target_time * (1.0 - 1e-12)) {
      const double cap = std::min(spec.largest_dt, target_time - solver.time());
      if (auto failure = solver.step(cap))
        throw std::runtime_error("three-grain " + spec.variant + ": numerical failure at step " +
                                 std::to_string(failure->step) + ": " + failure->what);
      const auto& row = solver.last_row();
      run.timing.largest_dt = std::max(run.timing.largest_dt, row.dt);
      const double force = std::abs(row.wall_force[static_cast<std::size_t>(platen)][1]);
      peak_force = std::max(peak_force, force);
      // One curve point per ten steps, the window's largest force: a contact peak can last fewer
      // than ten steps (at 80 m/s and h = 0.1 mm every tenth step missed the 5.1 MN/m peak and
      // topped out near 2.5 MN/m).
      window_force = std::max(window_force, force);
      if (solver.step_count() % 10 == 0) {
        run.curve_displacement.push_back(
            row.wall_displacement[static_cast<std::size_t>(platen)].norm());
        run.curve_force.push_back(window_force);
        window_force = 0.0;
      }
      if (run.thermal) {
        const auto& T = solver.particles().temperature;
        hottest_rise =
            std::max(hottest_rise, *std::max_element(T.begin(), T.end()) - initial_hottest);
      }
    }
    ThreeGrainFrame frame;
    frame.particles = solver.particles();
    const auto [reference, current] =
        body_pair(run.reference, row_of, frame.particles, run.top_body);
    frame.top_fragments =
        analysis::analyze_fragments(reference, current, analysis::FragmentOptions{}, false);
    frame.sample.variant = spec.variant;
    frame.sample.platen_speed = spec.platen_speed;
    frame.sample.displacement =
        solver.last_row().wall_displacement[static_cast<std::size_t>(platen)].norm();
    frame.sample.time = solver.time();
    summarize_top_grain(frame.top_fragments, frame.sample);
    frame.sample.peak_force = peak_force;
    frame.sample.largest_temperature_rise =
        run.thermal ? hottest_rise : std::numeric_limits<double>::quiet_NaN();
    // The full study's runs take up to an hour each: a line per sampled travel shows progress.
    std::fprintf(stderr,
                 "  three-grain %s: platen travel %.3g mm at step %lld, %.0f s; top grain %lld "
                 "fragments, %lld fines\n",
                 spec.variant.c_str(), 1e3 * frame.sample.displacement, solver.step_count(),
                 std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(),
                 frame.sample.fragments, frame.sample.fines);
    run.frames.push_back(std::move(frame));
  }
  run.timing.steps = solver.step_count();
  run.timing.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  announce_run("three-grain " + spec.variant + " " + cell_label(spec.cell_size), solver,
               run.timing.wall_seconds);
  const auto& last = solver.last_row();
  run.input_energy = mpm::energy_input(last);
  run.balance_error = last.balance_error;
  run.totals = last.totals;
  return run;
}

}  // namespace fragmpm::pipeline
