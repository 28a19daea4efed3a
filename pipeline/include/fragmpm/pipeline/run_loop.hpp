#pragma once
// Drives a Solver to its stop condition, writing frames, /series and checkpoints to a run file.
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>

#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/mpm/solver.hpp"

namespace fragmpm::pipeline {

struct RunLoopOptions {
  long long max_steps_override =
      std::numeric_limits<long long>::max();  ///< stop early (--max-steps)
  bool write_initial_frame = true;            ///< false when continuing from a checkpoint
  bool progress = false;                      ///< progress line with ETA on stderr (terminal only)
};

struct RunLoopResult {
  bool failed = false;
  mpm::NumericalFailure failure;
  long long steps = 0;
  int frames = 0;
  double wall_seconds = 0.0;
};

/// /meta of a new run file for `problem`: its scene, modules and wall names.
mpm::RunMeta run_meta(const mpm::Problem<2>& problem);

/// Restores `solver` (built from the file's scene) from `file`'s checkpoint and drops the frames
/// and series rows written after it. False, and nothing changed, when the file has no checkpoint.
bool restore_from_checkpoint(mpm::Solver<2>& solver, mpm::RunFile<2>& file);

/// Runs until the problem's stop condition (or the override). A numerical failure is recorded in
/// the file's /meta, the frames and series written so far stay, and the result says failed.
RunLoopResult run_loop(mpm::Solver<2>& solver, mpm::RunFile<2>& file,
                       const RunLoopOptions& options);

}  // namespace fragmpm::pipeline
