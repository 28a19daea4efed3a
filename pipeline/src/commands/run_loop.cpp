#include "fragmpm/pipeline/run_loop.hpp"

#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <utility>
#include <vector>

#include "fragmpm/mpm/current_domain.hpp"

namespace fragmpm::pipeline {

namespace {

/// Index of the last output time at or before t; output k is at k·interval (multiplied, never
/// accumulated, so a restarted run hits the same times bit for bit).
long long output_index_at(double t, double interval) {
  return static_cast<long long>(std::floor(t / interval * (1.0 + 1e-12) + 1e-12));
}

class ProgressLine {
 public:
  explicit ProgressLine(bool enabled) : enabled_(enabled && isatty(STDERR_FILENO)) {}
  void update(long long step, double time, double fraction) {
    if (!enabled_) return;
    const auto now = std::chrono::steady_clock::now();
    if (now - last_ < std::chrono::milliseconds(500)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    const double eta = fraction > 1e-6 ? elapsed * (1.0 - fraction) / fraction : 0.0;
    std::fprintf(stderr, "\r  step %lld  t = %.4g s  %5.1f %%  elapsed %.0f s  ETA %.0f s   ", step,
                 time, 100.0 * fraction, elapsed, eta);
    shown_ = true;
  }
  ~ProgressLine() {
    if (shown_) std::fprintf(stderr, "\n");
  }

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  std::chrono::steady_clock::time_point last_ = start_;
};

}  // namespace

mpm::RunMeta run_meta(const mpm::Problem<2>& problem) {
  mpm::RunMeta meta;
  meta.scene_path = problem.scene_path;
  meta.scene_text = problem.scene_text;
  meta.modules = mpm::plan_modules<2>(problem);
  for (const auto& w : problem.walls) meta.wall_names.push_back(w.name);
  return meta;
}

bool restore_from_checkpoint(mpm::Solver<2>& solver, mpm::RunFile<2>& file) {
  std::optional<mpm::Checkpoint<2>> checkpoint = file.read_checkpoint();
  if (!checkpoint) return false;
  file.truncate_after(checkpoint->step);
  solver.restore(checkpoint->time, checkpoint->step, checkpoint->totals,
                 std::move(checkpoint->particles), std::move(checkpoint->phase_field));
  return true;
}

RunLoopResult run_loop(mpm::Solver<2>& solver, mpm::RunFile<2>& file,
                       const RunLoopOptions& options) {
  const auto wall_start = std::chrono::steady_clock::now();
  const auto& problem = solver.problem();
  const auto& stop = problem.stop;
  const double interval = problem.output.interval;
  const std::vector<std::string>& fields = problem.output.fields;
  RunLoopResult result;
  std::vector<mpm::SeriesRow<2>> pending;

  auto checkpoint = [&] {
    file.append_series(pending);
    pending.clear();
    mpm::Checkpoint<2> state;
    state.time = solver.time();
    state.step = solver.step_count();
    state.totals = solver.accumulators();
    state.particles = solver.particles();
    state.phase_field = solver.phase_field_warm_start();
    file.write_checkpoint(state);
    file.flush();
  };
  auto write_frame = [&] {
    // A frame holds each particle's current domain (current_domain.hpp); the checkpoint keeps the
    // solver's own.
    const mpm::ShapeFunctionKind kind = solver.problem().grid.shape_function;
    if (kind == mpm::ShapeFunctionKind::cpdi)
      file.write_frame(solver.step_count(), solver.time(), solver.particles(), fields);
    else
      file.write_frame(solver.step_count(), solver.time(),
                       mpm::with_current_domains<2>(solver.particles(), kind), fields);
    ++result.frames;
    checkpoint();
  };

  if (options.write_initial_frame) {
    pending.push_back(solver.last_row());
    write_frame();
  }
  long long output_index = interval > 0.0 ? output_index_at(solver.time(), interval) : 0;
  long long last_frame_step = solver.step_count();
  const long long step_limit =
      std::min(stop.max_steps, options.max_steps_override == std::numeric_limits<long long>::max()
                                   ? stop.max_steps
                                   : solver.step_count() + options.max_steps_override);
  ProgressLine progress(options.progress);

  auto platen_travel = [&] {
    return stop.platen >= 0 ? solver.wall_displacement(static_cast<std::size_t>(stop.platen)).norm()
                            : 0.0;
  };
  auto finished = [&] {
    return solver.time() >= stop.end_time * (1.0 - 1e-12) || solver.step_count() >= step_limit ||
           platen_travel() >= stop.platen_displacement;
  };

  while (!finished()) {
    double cap = std::numeric_limits<double>::infinity();
    if (std::isfinite(stop.end_time)) cap = stop.end_time - solver.time();
    if (interval > 0.0) cap = std::min(cap, (output_index + 1) * interval - solver.time());
    if (auto failure = solver.step(cap)) {
      file.append_series(pending);
      pending.clear();
      file.write_failure(failure->what);
      file.flush();
      result.failed = true;
      result.failure = *failure;
      break;
    }
    ++result.steps;
    pending.push_back(solver.last_row());
    if (interval > 0.0 && solver.time() >= (output_index + 1) * interval * (1.0 - 1e-12)) {
      output_index = output_index_at(solver.time(), interval);
      write_frame();
      last_frame_step = solver.step_count();
    }
    double fraction = 0.0;
    if (std::isfinite(stop.end_time)) fraction = std::max(fraction, solver.time() / stop.end_time);
    if (step_limit < std::numeric_limits<long long>::max())
      fraction = std::max(fraction, double(solver.step_count()) / double(step_limit));
    if (std::isfinite(stop.platen_displacement))
      fraction = std::max(fraction, platen_travel() / stop.platen_displacement);
    progress.update(solver.step_count(), solver.time(), std::min(fraction, 1.0));
  }
  if (!result.failed && solver.step_count() != last_frame_step) write_frame();
  result.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start).count();
  return result;
}

}  // namespace fragmpm::pipeline
