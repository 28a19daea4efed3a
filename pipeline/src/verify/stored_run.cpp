// Verification runs kept in a run file and continued from its checkpoint (stored_run.hpp).
#include "fragmpm/pipeline/stored_run.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <stdexcept>

#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"
#include "fragmpm/pipeline/run_loop.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

StoredRun run_stored(mpm::Solver<2>& solver, const std::string& path, long long max_steps,
                     const std::string& what) {
  const auto& problem = solver.problem();
  std::optional<mpm::RunFile<2>> file;
  bool continuing = false;
  if (std::filesystem::exists(path)) {
    try {
      file.emplace(mpm::RunFile<2>::open_existing(path));
    } catch (const mpm::RunFileError& e) {
      throw std::invalid_argument(std::string(e.what()) +
                                  "; this case keeps its run there: move the file away");
    }
    if (file->meta().scene_text != problem.scene_text)
      throw std::invalid_argument(
          path +
          " holds a run of another scene than this case's (an earlier build's, or other "
          "options); move it away to start this run afresh");
    if (!restore_from_checkpoint(solver, *file))
      throw std::invalid_argument(path +
                                  " has no /checkpoint to continue from; move it away to "
                                  "start this run afresh");
    continuing = true;
  } else {
    std::filesystem::create_directories(std::filesystem::path(path).parent_path());
    file.emplace(mpm::RunFile<2>::create(path, run_meta(problem), false));
  }
  const double end_time = problem.stop.end_time;
  StoredRun stored;
  if (solver.time() < end_time * (1.0 - 1e-12)) {
    std::fprintf(stderr, "  %s: %s %s at step %lld, t = %.4g s of %.4g s\n", what.c_str(),
                 continuing ? "continuing" : "starting", path.c_str(), solver.step_count(),
                 solver.time(), end_time);
    RunLoopOptions options;
    options.write_initial_frame = !continuing;
    options.progress = true;
    if (max_steps > 0) options.max_steps_override = max_steps;
    const RunLoopResult result = run_loop(solver, *file, options);
    stored.wall_seconds = result.wall_seconds;
    if (result.failed)
      throw std::runtime_error(what + ": numerical failure at step " +
                               std::to_string(result.failure.step) + ": " + result.failure.what +
                               " (the frames before it stay in " + path + ")");
  }
  file.reset();  // closed before it is read back
  stored.finished = solver.time() >= end_time * (1.0 - 1e-12);
  stored.steps = solver.step_count();
  const mpm::RunSeries series = mpm::RunFileReader::open(path).read_series({"dt"});
  for (double dt : series.column("dt")) stored.largest_dt = std::max(stored.largest_dt, dt);
  if (stored.finished)
    announce_run(what, solver, stored.wall_seconds);
  else
    std::fprintf(stderr,
                 "  %s: stopped at step %lld, t = %.4g s of %.4g s, checkpoint in %s; the same "
                 "command continues the run\n",
                 what.c_str(), solver.step_count(), solver.time(), end_time, path.c_str());
  return stored;
}

}  // namespace fragmpm::pipeline
