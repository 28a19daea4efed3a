// Two rings colliding ([KT19] §5.2; docs/verification.md, `two-rings`): two phase-field rings fly
// at each other with ±u₀ and friction 0.65 between them. The paper: at u₀ = 0.01 mm/µs each ring
// ends in 2 fragments, at 0.02 mm/µs in 5, and the crack energy stops growing once the cracks have
// run (its Fig. 17b).
//
// Counting. Each ring's particles are labelled into fragments as `fragmpm analyze` does (masked at
// d ≥ 0.99, connected in the reference and the current configuration). A piece is a fragment of
// at least 1 % of its ring's mass: the paper counts the pieces its figures show, and a chip of a
// few particles crushed at the contact is not one of them. The count of all resolved fragments
// (4 particles or more) is reported beside it.
#include <fmt/core.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <vector>

#include "fragmpm/analysis/frame_fragments.hpp"
#include "fragmpm/analysis/frame_reference.hpp"
#include "fragmpm/mpm/current_domain.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "phase_field_snapshots.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double piece_fraction = 0.01;  // of the ring's mass: the smallest fragment counted

struct RingCount {
  int pieces = 0;     ///< fragments of at least piece_fraction of the ring's mass
  int fragments = 0;  ///< resolved fragments (4 particles or more)
};

struct RingsState {
  double time = 0.0;
  double fracture_energy = 0.0;  ///< [J/m]
  RingCount ring[2];
};

mpm::Particles<2> body_rows(const mpm::Particles<2>& all, int body) {
  std::vector<std::size_t> rows;
  for (std::size_t p = 0; p < all.size(); ++p)
    if (all.body[p] == body) rows.push_back(p);
  return all.select(rows);
}

/// ring_mass: each ring's mass at the start [kg/m].
RingsState observe(const mpm::Solver<2>& solver, const mpm::Particles<2>& first,
                   const double (&ring_mass)[2]) {
  RingsState s;
  s.time = solver.time();
  s.fracture_energy = solver.accumulators().fracture_energy;
  const analysis::FrameReference matched = analysis::frame_reference(first, solver.particles());
  const mpm::Particles<2> drawn =
      mpm::with_current_domains<2>(solver.particles(), solver.problem().grid.shape_function);
  for (int body = 0; body < 2; ++body) {
    const mpm::Particles<2> reference = body_rows(matched.particles, body);
    const mpm::Particles<2> current = body_rows(drawn, body);
    const analysis::FrameFragments frame =
        analysis::analyze_fragments(reference, current, analysis::FragmentOptions{}, false);
    for (const auto& f : frame.fragments) {
      ++s.ring[body].fragments;
      s.ring[body].pieces += f.mass >= piece_fraction * ring_mass[body];
    }
  }
  return s;
}

/// `figure_times_us`: the paper's phase-field figure of this speed; `figure_directory`: where it
/// goes (empty: nowhere).
std::vector<VerifyRow> run_rings(double speed, int paper_pieces, double cell_size, int level,
                                 const std::vector<double>& figure_times_us,
                                 const std::string& figure_directory) {
  const std::string name = speed < 15.0 ? "10m/s" : "20m/s";
  std::map<std::string, std::string> overrides{{"output.interval", "0.0"}};
  overrides["grid.cell_size"] = toml_number(cell_size);
  overrides["bodies[0].velocity"] = fmt::format("[{}, 0.0]", toml_number(speed));
  overrides["bodies[1].velocity"] = fmt::format("[{}, 0.0]", toml_number(-speed));
  const std::string text = with_overrides(embedded_scene("paper/two-rings.toml"), overrides);
  mpm::Problem<2> problem = parse_scene(text, "scenes/paper/two-rings.toml");
  const mpm::Particles<2> first = problem.particles;
  double ring_mass[2] = {0.0, 0.0};
  for (std::size_t p = 0; p < first.size(); ++p) ring_mass[first.body[p]] += first.mass[p];
  mpm::Solver<2> solver(std::move(problem));
  std::vector<RingsState> history;
  PhaseFieldSnapshots snapshots = phase_field_snapshots(figure_times_us);
  take_snapshot(snapshots, solver);
  // Observed every 5 µs (the figures' time points are multiples of it); fragments counted at every
  // fifth observation.
  int observations = 0;
  const TimedRun run = run_until(
      solver, solver.problem().stop.end_time, "two-rings " + name + " " + cell_label(cell_size),
      5e-6, [&](const mpm::Solver<2>& s) {
        take_snapshot(snapshots, s);
        const bool at_end = s.time() >= s.problem().stop.end_time * (1.0 - 1e-12);
        if (++observations % 5 != 0 && !at_end) return;
        history.push_back(observe(s, first, ring_mass));
        const RingsState& r = history.back();
        std::fprintf(stderr,
                     "    t = %5.0f us: pieces %d | %d (fragments %d | %d), crack energy %.1f "
                     "J/m\n",
                     r.time * 1e6, r.ring[0].pieces, r.ring[1].pieces, r.ring[0].fragments,
                     r.ring[1].fragments, r.fracture_energy);
      });
  if (!figure_directory.empty()) {
    char stem[64];
    std::snprintf(stem, sizeof stem, "%s-h%gmm-phase-field.png", name == "10m/s" ? "10ms" : "20ms",
                  cell_size * 1e3);
    write_phase_field_panels(snapshots, (std::filesystem::path(figure_directory) / stem).string(),
                             "Two rings at " + name + ", " + cell_label(cell_size));
  }
  const RingsState& last = history.back();
  // When the crack energy stopped growing: the first observation within 2 % of the final value.
  double settled = last.time;
  for (const RingsState& r : history)
    if (r.fracture_energy >= 0.98 * last.fracture_energy) {
      settled = r.time;
      break;
    }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  auto row = [&](const std::string& metric, double value, double reference) {
    return metric_row(level_row("two-rings", name, level, cell_size, solver, run), metric, value,
                      reference);
  };
  std::vector<VerifyRow> rows;
  const char* side[2] = {"left", "right"};
  for (int body = 0; body < 2; ++body) {
    VerifyRow pieces =
        row(std::string(side[body]) + "_ring_pieces (paper " + std::to_string(paper_pieces) + ")",
            last.ring[body].pieces, paper_pieces);
    pieces.target_low = paper_pieces;
    pieces.target_high = paper_pieces;
    rows.push_back(pieces);
    rows.push_back(
        row(std::string(side[body]) + "_ring_fragments", last.ring[body].fragments, nan));
  }
  rows.push_back(row("final_crack_energy_J/m", last.fracture_energy, nan));
  rows.push_back(row("crack_energy_settled_us (98 % of final)", settled * 1e6, nan));
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_two_rings(const VerifyOptions& options) {
  // Quick: h = l₀ = 1 mm; the paper's h = 0.5 mm (l₀ = 1 mm) is the full level.
  std::vector<VerifyRow> rows;
  const double cells[] = {1e-3, 0.5e-3};
  const std::string figures = case_directory(options, "two-rings");
  // [KT19] Fig. 18 (10 m/s) and Fig. 20 (20 m/s) show the phase field at these times [µs].
  const std::vector<double> slow_times{0, 75, 95, 200, 400, 625};
  const std::vector<double> fast_times{0, 30, 45, 60, 400, 625};
  check_selection(options, "two-rings", {"10m/s", "20m/s"}, options.quick ? 1 : 2);
  for (int level = 0; level < (options.quick ? 1 : 2); ++level) {
    if (selected(options, "10m/s", level))
      for (auto& r : run_rings(10.0, 2, cells[level], level, slow_times, figures))
        rows.push_back(r);
    if (selected(options, "20m/s", level))
      for (auto& r : run_rings(20.0, 5, cells[level], level, fast_times, figures))
        rows.push_back(r);
  }
  return rows;
}

}  // namespace fragmpm::pipeline
