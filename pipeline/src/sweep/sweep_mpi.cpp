// `mpirun -n R fragmpm sweep SWEEP -o DIR --mpi`: dynamic assignment of members to ranks. Rank 0
// only assigns (it answers each request with the next unfinished member, or with "no more"), so a
// long member holds one rank while the others go on with the short ones. Built only when CMake
// found MPI (option FRAGMPM_MPI); without it sweep_mpi_available() is false and `--mpi` explains
// how to enable it.
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/sweep_members.hpp"
#include "fragmpm/pipeline/sweep_runner.hpp"
#include "fragmpm/pipeline/sweep_schedule.hpp"

#ifdef FRAGMPM_HAVE_MPI
#include <mpi.h>
#endif

namespace fragmpm::pipeline {

#ifndef FRAGMPM_HAVE_MPI

bool sweep_mpi_available() {
  return false;
}

int run_sweep_mpi(const std::string&, SweepRunOptions, bool) {
  std::fprintf(stderr, "fragmpm sweep: this build has no MPI\n");
  return 2;
}

#else

namespace fs = std::filesystem;

namespace {

constexpr int kTagWork = 1;    // rank 0 → worker: member index, or −1 = no more work
constexpr int kTagResult = 2;  // worker → rank 0: {member index or −1, outcome, wall seconds}

/// Outcome codes in a result message.
enum Outcome { kNone = 0, kDone = 1, kFailed = 2, kInterrupted = 3 };

/// Threads per member: the processes mpirun started on this node share its cores.
int default_threads() {
  const unsigned hw = std::thread::hardware_concurrency();
  int local = 1;
  if (const char* s = std::getenv("OMPI_COMM_WORLD_LOCAL_SIZE")) local = std::max(1, std::atoi(s));
  // Rank 0 only assigns work and sleeps in MPI_Recv, so it does not count against the cores.
  if (local > 1) --local;
  return std::max(1, static_cast<int>(hw > 0 ? hw : 1) / local);
}

int coordinator(const SweepSpec& spec, const SweepRunOptions& o, int ranks) {
  const std::vector<std::size_t> todo = unfinished_members(spec, o.dir);
  std::fprintf(stderr,
               "fragmpm sweep: %zu members, %zu finished, %zu to run on %d worker rank(s) with %d "
               "thread(s) each\n",
               spec.members.size(), spec.members.size() - todo.size(), todo.size(), ranks - 1,
               o.threads);
  SweepProgress progress(spec.members.size(), spec.members.size() - todo.size(), ranks - 1,
                         o.progress);
  std::size_t next = 0, running = 0, failed = 0, interrupted = 0;
  int active = ranks - 1;
  while (active > 0) {
    double msg[3];
    MPI_Status st;
    MPI_Recv(msg, 3, MPI_DOUBLE, MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &st);
    const int member = static_cast<int>(msg[0]);
    const int outcome = static_cast<int>(msg[1]);
    if (member >= 0) {
      --running;
      const char* status = outcome == kDone     ? "done"
                           : outcome == kFailed ? "failed"
                                                : "interrupted";
      if (outcome == kFailed) ++failed;
      if (outcome == kInterrupted) ++interrupted;
      progress.report(spec.members[static_cast<std::size_t>(member)].name, status, msg[2], running);
    }
    int assign = -1;
    if (next < todo.size() && !stop_requested() && outcome != kInterrupted) {
      assign = static_cast<int>(todo[next++]);
      ++running;
    }
    if (assign < 0) --active;
    MPI_Send(&assign, 1, MPI_INT, st.MPI_SOURCE, kTagWork, MPI_COMM_WORLD);
    progress.refresh(running);
  }
  write_manifest(spec, o.dir);
  if (interrupted > 0 || stop_requested() || next < todo.size()) return 130;
  return failed > 0 ? 1 : 0;
}

void worker(const SweepSpec& spec, const SweepRunOptions& o) {
  const std::string exe = self_executable();
  double msg[3] = {-1.0, kNone, 0.0};
  for (;;) {
    MPI_Send(msg, 3, MPI_DOUBLE, 0, kTagResult, MPI_COMM_WORLD);
    int member = -1;
    MPI_Recv(&member, 1, MPI_INT, 0, kTagWork, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (member < 0) return;
    const SweepMember& m = spec.members[static_cast<std::size_t>(member)];
    const MemberStatus s =
        run_member({(fs::path(o.dir) / m.name).string(), exe, o.threads, spec.analysis});
    msg[0] = member;
    msg[1] = s.status == "done" ? kDone : s.status == "failed" ? kFailed : kInterrupted;
    msg[2] = s.wall_seconds;
  }
}

}  // namespace

bool sweep_mpi_available() {
  return true;
}

int run_sweep_mpi(const std::string& sweep_path, SweepRunOptions o, bool threads_given) {
  MPI_Init(nullptr, nullptr);
  int rank = 0, ranks = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  install_stop_handlers();
  if (!threads_given) o.threads = default_threads();
  int code = 0;
  // Rank 0 checks every member scene and prepares DIR; the others wait for its verdict and then
  // build the same member list without compiling.
  int ok = 1;
  SweepSpec spec;
  if (rank == 0) {
    try {
      spec = read_sweep(sweep_path, o.dir, true);
      prepare_sweep_dir(spec, o.dir);
    } catch (const SceneError& e) {
      std::fprintf(stderr, "fragmpm sweep: %s\n", e.what());
      ok = 0;
      code = 2;
    } catch (const std::exception& e) {
      std::fprintf(stderr, "fragmpm sweep: %s\n", e.what());
      ok = 0;
      code = 1;
    }
  }
  MPI_Bcast(&ok, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  if (ok && ranks < 2) {
    if (rank == 0)
      std::fprintf(stderr,
                   "fragmpm sweep: --mpi needs at least 2 ranks (rank 0 assigns, the others run "
                   "members): mpirun -n 3 fragmpm sweep ... --mpi\n");
    ok = 0;
    code = 2;
  }
  if (ok) {
    if (rank == 0) {
      code = coordinator(spec, o, ranks);
    } else {
      try {
        spec = read_sweep(sweep_path, o.dir, false);
      } catch (const std::exception& e) {
        std::fprintf(stderr, "fragmpm sweep (rank %d): %s\n", rank, e.what());
        MPI_Abort(MPI_COMM_WORLD, 1);
      }
      worker(spec, o);
    }
  }
  MPI_Bcast(&code, 1, MPI_INT, 0, MPI_COMM_WORLD);
  MPI_Finalize();
  return code;
}

#endif

}  // namespace fragmpm::pipeline
