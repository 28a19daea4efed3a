#pragma once
// Handing a sweep's unfinished members to workers: local processes (`--jobs N`), MPI ranks
// (`--mpi`, rank 0 assigns members as ranks ask for work) or one Slurm array task (`--member K`),
// with a progress line (members done, failed, running, ETA).
#include <cstddef>
#include <string>
#include <vector>

#include "fragmpm/pipeline/sweep_file.hpp"

namespace fragmpm::pipeline {

struct SweepRunOptions {
  std::string dir;
  int jobs = 1;     ///< members at once (local)
  int threads = 1;  ///< OpenMP threads per member
  bool progress = true;
};

/// Tallies of one sweep invocation, for the progress line and the exit code.
struct SweepTally {
  std::size_t total = 0;    ///< members in the sweep
  std::size_t skipped = 0;  ///< finished before this invocation
  std::size_t done = 0, failed = 0, interrupted = 0;
};

/// Indices of the members without a "done" status.
std::vector<std::size_t> unfinished_members(const SweepSpec& spec, const std::string& dir);

/// Runs `todo` with `options.jobs` members at once; writes the manifest at the end.
SweepTally run_sweep_local(const SweepSpec& spec, const std::vector<std::size_t>& todo,
                           const SweepRunOptions& options);

/// Prints "sweep: D/T done, F failed, R running, ETA …" (on a terminal in place, else one line).
class SweepProgress {
 public:
  SweepProgress(std::size_t total, std::size_t already_done, int workers, bool enabled);
  void report(const std::string& name, const std::string& status, double wall_seconds,
              std::size_t running);
  void refresh(std::size_t running);
  ~SweepProgress();

 private:
  std::string line(std::size_t running) const;
  std::size_t total_, done_, failed_ = 0, finished_now_ = 0;
  int workers_;
  bool enabled_, tty_, shown_ = false;
  double start_;
};

/// Whether this build has MPI (the CMake option FRAGMPM_MPI found OpenMPI).
bool sweep_mpi_available();

/// Under mpirun: rank 0 reads and checks the sweep (exit 2 on a bad one, on every rank), prepares
/// DIR and assigns the unfinished members one at a time to the ranks that ask for work; ranks
/// 1 … R−1 run them. Returns the exit code for this rank. Only in builds with MPI.
int run_sweep_mpi(const std::string& sweep_path, SweepRunOptions options, bool threads_given);

/// Writes DIR/sweep.slurm, a job-array script with one array task per member
/// (`fragmpm sweep SWEEP -o DIR --member $SLURM_ARRAY_TASK_ID`), and returns its path.
std::string write_slurm_script(const SweepSpec& spec, const std::string& dir, int threads,
                               const std::string& executable);

}  // namespace fragmpm::pipeline
