#pragma once
// A verification run kept in a run file in the case's folder, for the runs at a paper's cell that
// take longer than one sitting: `--max-steps N` stops it after N steps with a checkpoint, and the
// same command continues it from there. The case then reads its observations from the frames.
#include <string>

#include "fragmpm/mpm/solver.hpp"

namespace fragmpm::pipeline {

struct StoredRun {
  bool finished = false;      ///< the run reached its scene's end time
  long long steps = 0;        ///< the run's steps in all
  double wall_seconds = 0.0;  ///< this invocation's
  double largest_dt = 0.0;    ///< [s], over the whole run
};

/// Runs `solver` (built from its scene, nothing stepped yet) to its end time in the run file
/// `path`, writing frames at the scene's output interval and a checkpoint with each frame. When
/// `path` exists and holds a run of the same scene text, the solver is restored from its
/// checkpoint and the run continues (a finished run is only reopened); `max_steps` > 0 stops this
/// invocation after that many steps. Throws std::invalid_argument when `path` holds another
/// scene's run or no checkpoint (the user's file is left as it is), std::runtime_error naming
/// `what` on a numerical failure (the frames written so far stay in `path`). Prints a line when it
/// starts, stops or finishes.
StoredRun run_stored(mpm::Solver<2>& solver, const std::string& path, long long max_steps,
                     const std::string& what);

}  // namespace fragmpm::pipeline
