#pragma once
// Shared driver of the verification cases that run a scene to an end time and look at the state
// along the way.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/verify.hpp"

namespace fragmpm::pipeline {

/// DIR/`case_name` for a case's figures, or empty when the options write no files.
inline std::string case_directory(const VerifyOptions& options, const std::string& case_name) {
  return options.output_directory.empty()
             ? std::string()
             : (std::filesystem::path(options.output_directory) / case_name).string();
}

/// "h = 5 mm"-style label of a level for progress lines.
inline std::string cell_label(double cell_size) {
  char text[32];
  std::snprintf(text, sizeof text, "h = %.4g mm", cell_size * 1e3);
  return text;
}

/// One progress line per finished run on stderr (verification runs take minutes each), with the
/// run's unexplained energy: a case that checks a dissipation or a fragment count is only as good
/// as the balance of the run it reads.
inline void announce_run(const std::string& what, const mpm::Solver<2>& solver,
                         double wall_seconds) {
  const mpm::SeriesRow<2>& row = solver.last_row();
  std::fprintf(stderr, "  %s: %zu particles, %lld steps to t = %.4g s in %.1f s", what.c_str(),
               solver.particles().size(), solver.step_count(), solver.time(), wall_seconds);
  const double input = mpm::energy_input(row);
  if (solver.problem().time.damping > 0.0)
    std::fprintf(stderr, "; grid damping on, so the balance holds what it removed\n");
  else if (input > 0.0)
    std::fprintf(stderr, "; balance error %+.4g J/m, %.2f %% of the input %.4g J/m\n",
                 row.balance_error, 100.0 * row.balance_error / input, input);
  else
    std::fprintf(stderr, "\n");
  // Which solve a phase-field run's time went to: the multigrid switch happens on its own, once
  // the crack-block iterations say the system needs it (phase_field_warm_start.hpp).
  const mpm::PhaseFieldWork& work = solver.phase_field_work();
  if (work.runs > 0)
    std::fprintf(stderr,
                 "    phase field: %lld solves, %lld preconditioned by multigrid (%lld with levels "
                 "kept from an earlier step), %lld direct, "
                 "%.1f conjugate-gradient iterations a solve, %.1f s (%.0f %% of the run)\n",
                 work.runs, work.multigrid_solves, work.kept_levels, work.direct_runs,
                 double(work.iterations) / double(work.runs), work.seconds,
                 wall_seconds > 0.0 ? 100.0 * work.seconds / wall_seconds : 0.0);
}

struct TimedRun {
  double wall_seconds = 0.0;
  long long steps = 0;
  double largest_dt = 0.0;  ///< [s]
};

/// Steps `solver` to `end_time` [s], calling observe(solver) after every step (or, when
/// `observe_interval` > 0, whenever that much simulated time has passed and at the end).
/// A numerical failure becomes std::runtime_error naming the case.
template <class Observe>
TimedRun run_until(mpm::Solver<2>& solver, double end_time, const std::string& case_name,
                   double observe_interval, Observe&& observe) {
  TimedRun run;
  const auto start = std::chrono::steady_clock::now();
  double next_observation = solver.time() + observe_interval;
  while (solver.time() < end_time * (1.0 - 1e-12)) {
    const double cap = observe_interval > 0.0 ? std::min(end_time, next_observation) : end_time;
    if (auto failure = solver.step(cap - solver.time()))
      throw std::runtime_error(case_name + ": numerical failure at step " +
                               std::to_string(failure->step) + ": " + failure->what);
    run.largest_dt = std::max(run.largest_dt, solver.last_row().dt);
    if (observe_interval <= 0.0 || solver.time() >= next_observation * (1.0 - 1e-12) ||
        solver.time() >= end_time * (1.0 - 1e-12)) {
      observe(solver);
      if (observe_interval > 0.0)
        while (next_observation <= solver.time() * (1.0 + 1e-12))
          next_observation += observe_interval;
    }
  }
  run.steps = solver.step_count();
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  announce_run(case_name, solver, run.wall_seconds);
  return run;
}

/// A row with the level data filled in.
inline VerifyRow level_row(const std::string& case_name, const std::string& variant, int level,
                           double cell_size, const mpm::Solver<2>& solver, const TimedRun& run) {
  VerifyRow r;
  r.case_name = case_name;
  r.variant = variant;
  r.level = level;
  r.cell_size = cell_size;
  r.particles = static_cast<long long>(solver.particles().size());
  r.dt = run.largest_dt;
  r.steps = run.steps;
  r.wall_seconds = run.wall_seconds;
  return r;
}

/// Appends one run's rows to `rows`; the full set, whose runs at the papers' cells take up to
/// hours each, also prints them as soon as the run ends.
inline void append_run_rows(const VerifyOptions& options, const std::string& variant,
                            double cell_size, std::vector<VerifyRow> run_rows,
                            std::vector<VerifyRow>& rows) {
  for (VerifyRow& r : run_rows) {
    if (!options.quick)
      std::fprintf(stderr, "    %s h = %g mm: %s = %.4g\n", variant.c_str(), cell_size * 1e3,
                   r.metric.c_str(), r.value);
    rows.push_back(std::move(r));
  }
}

/// |value − reference| / |reference|.
inline double relative_error(double value, double reference) {
  return std::abs(value - reference) / std::abs(reference);
}

/// `level` (a level_row) for `metric`: its error is relative to a finite, non-zero reference, and
/// the value itself where there is none (NaN: a reading reported without a reference).
inline VerifyRow metric_row(VerifyRow level, const std::string& metric, double value,
                            double reference) {
  level.metric = metric;
  level.value = value;
  level.reference = reference;
  level.error =
      std::isfinite(reference) && reference != 0.0 ? relative_error(value, reference) : value;
  return level;
}

/// `text` with `line` inserted after the first line that holds `key` (e.g. a material's
/// `anisotropy = {…}` after its `fracture_energy`).
inline std::string insert_after_line(std::string text, const std::string& key,
                                     const std::string& line) {
  const auto at = text.find(key);
  if (at == std::string::npos) throw std::logic_error("scene text without '" + key + "'");
  text.insert(text.find('\n', at) + 1, line + "\n");
  return text;
}

}  // namespace fragmpm::pipeline
