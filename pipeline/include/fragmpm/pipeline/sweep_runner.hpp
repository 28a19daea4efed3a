#pragma once
// Running one sweep member as child processes of this program (README "Many runs"): `fragmpm run
// scene.toml -o run.h5` and then `fragmpm analyze run.h5 --csv-only` in the member's folder. A
// child process keeps a member's crash, exit code and memory apart from the sweep and from the
// others; the same function serves `--jobs N`, MPI ranks and Slurm array tasks.
#include <string>

#include "fragmpm/pipeline/sweep_file.hpp"
#include "fragmpm/pipeline/sweep_members.hpp"

namespace fragmpm::pipeline {

struct MemberJob {
  std::string dir;         ///< the member's folder, holding scene.toml
  std::string executable;  ///< this program (self_executable())
  int threads = 1;         ///< OpenMP threads of the member's run
  SweepAnalysis analysis;
};

/// This program's path (/proc/self/exe), for the child processes.
std::string self_executable();

/// Runs the member from the start (its old run file, fragment tables and status are removed),
/// then writes status.txt: "done" when both children exit 0, "failed" with the first non-zero exit
/// code otherwise. When a stop was requested (SIGINT/SIGTERM) while it ran, nothing is written and
/// the returned status is "interrupted", so that the next sweep runs it again.
MemberStatus run_member(const MemberJob& job);

/// Installs SIGINT and SIGTERM handlers that ask every running member's child to stop (SIGTERM)
/// and make stop_requested() true. Finished members stay as they are.
void install_stop_handlers();
bool stop_requested();

}  // namespace fragmpm::pipeline
