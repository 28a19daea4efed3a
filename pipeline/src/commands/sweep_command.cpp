// `fragmpm sweep SWEEP.toml -o DIR [--jobs N] [--threads T] [--mpi] [--slurm] [--member K]`
// (README "Many runs"): every member scene is compiled first (exit 2 naming file, line and key of
// a bad one), then the unfinished members run; finished ones are skipped, never rewritten.
#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <thread>

#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/sweep_file.hpp"
#include "fragmpm/pipeline/sweep_members.hpp"
#include "fragmpm/pipeline/sweep_runner.hpp"
#include "fragmpm/pipeline/sweep_schedule.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {

struct SweepArguments {
  std::string sweep;
  std::string dir;
  int jobs = 1;
  int threads = 0;
  bool mpi = false;
  bool slurm = false;
  int member = 0;  ///< 1-based; 0 = all
  bool check = false;
  bool quiet = false;
};

int cores() {
  const unsigned n = std::thread::hardware_concurrency();
  return n > 0 ? static_cast<int>(n) : 1;
}

/// Runs member K alone (a Slurm array task), then rewrites the manifest under a lock, as other
/// tasks may be finishing at the same time.
int run_one_member(const SweepSpec& spec, const SweepArguments& a, int threads) {
  if (a.member < 1 || a.member > static_cast<int>(spec.members.size())) {
    std::fprintf(stderr, "fragmpm sweep: --member %d: the sweep has members 1 to %zu\n", a.member,
                 spec.members.size());
    return 2;
  }
  const SweepMember& m = spec.members[static_cast<std::size_t>(a.member - 1)];
  const fs::path dir = fs::path(a.dir) / m.name;
  int code = 0;
  if (member_finished(dir.string())) {
    std::fprintf(stderr, "fragmpm sweep: member %s is finished; skipped\n", m.name.c_str());
  } else {
    const MemberStatus s = run_member({dir.string(), self_executable(), threads, spec.analysis});
    std::fprintf(stderr, "fragmpm sweep: member %s %s (exit code %d, %.1f s)\n", m.name.c_str(),
                 s.status.c_str(), s.exit_code, s.wall_seconds);
    code = s.status == "done" ? 0 : s.status == "interrupted" ? 130 : 1;
  }
  const std::string lock_path = (fs::path(a.dir) / ".manifest.lock").string();
  const int fd = open(lock_path.c_str(), O_CREAT | O_RDWR, 0644);
  if (fd >= 0) flock(fd, LOCK_EX);
  write_manifest(spec, a.dir);
  if (fd >= 0) close(fd);
  return code;
}

int execute(const SweepArguments& a) {
  if (a.jobs < 1) {
    std::fprintf(stderr, "fragmpm sweep: --jobs %d: expected at least 1\n", a.jobs);
    return 2;
  }
  if (a.mpi && !sweep_mpi_available()) {
    std::fprintf(stderr,
                 "fragmpm sweep: --mpi: this fragmpm was built without MPI. Install OpenMPI "
                 "(tools/install-deps.sh installs libopenmpi-dev and openmpi-bin), then configure "
                 "again with MPI on (cmake -S . -B build -DFRAGMPM_MPI=ON) and rebuild; or run "
                 "on one machine with --jobs N, or on a cluster with --slurm.\n");
    return 2;
  }
  if (a.mpi) {
    SweepRunOptions o;
    o.dir = a.dir;
    o.threads = a.threads;
    o.progress = !a.quiet;
    return run_sweep_mpi(a.sweep, o, a.threads > 0);
  }
  try {
    install_stop_handlers();
    const SweepSpec spec = read_sweep(a.sweep, a.dir, true);
    std::fprintf(stderr, "fragmpm sweep: %zu members, every member scene compiles\n",
                 spec.members.size());
    if (a.check) {
      for (const SweepMember& m : spec.members)
        std::fprintf(stderr, "  %s  %s\n", m.name.c_str(), describe_member(spec, m).c_str());
      return 0;
    }
    prepare_sweep_dir(spec, a.dir);
    const int jobs = a.jobs;
    const int threads = a.threads > 0 ? a.threads : std::max(1, cores() / jobs);
    if (jobs * threads > cores())
      std::fprintf(stderr,
                   "fragmpm sweep: %d jobs x %d threads exceed the %d cores; members will share "
                   "cores\n",
                   jobs, threads, cores());
    if (a.slurm) {
      const std::string script = write_slurm_script(spec, a.dir, threads, self_executable());
      write_manifest(spec, a.dir);
      std::fprintf(stderr, "fragmpm sweep: wrote %s; submit it with: sbatch %s\n", script.c_str(),
                   script.c_str());
      return 0;
    }
    if (a.member > 0) return run_one_member(spec, a, threads);
    const std::vector<std::size_t> todo = unfinished_members(spec, a.dir);
    std::fprintf(stderr,
                 "fragmpm sweep: %zu finished, %zu to run, %d at a time with %d thread(s) each\n",
                 spec.members.size() - todo.size(), todo.size(), jobs, threads);
    SweepRunOptions o{a.dir, jobs, threads, !a.quiet};
    const SweepTally t = run_sweep_local(spec, todo, o);
    std::fprintf(stderr,
                 "fragmpm sweep: %zu done now, %zu finished before, %zu failed, %zu interrupted; "
                 "manifest %s\n",
                 t.done, t.skipped, t.failed, t.interrupted,
                 (fs::path(a.dir) / "manifest.csv").string().c_str());
    if (t.interrupted > 0 || stop_requested()) return 130;
    return t.failed > 0 ? 1 : 0;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fragmpm sweep: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fragmpm sweep: %s\n", e.what());
    return 1;
  }
}

}  // namespace

void add_sweep_command(CLI::App& app, CommandResult& result) {
  auto a = std::make_shared<SweepArguments>();
  CLI::App* c = app.add_subcommand(
      "sweep",
      "Many runs: the members of a sweep file (Weibull seeds, varied scene keys), each run and "
      "analysed in DIR/NNNN/, with DIR/manifest.csv; rerunning skips finished members");
  c->add_option("sweep", a->sweep, "Sweep file (TOML, README \"Many runs\")")->required();
  c->add_option("-o,--output", a->dir, "Sweep directory")->required();
  c->add_option("-j,--jobs", a->jobs, "Members run at once on this machine")->capture_default_str();
  c->add_option("--threads", a->threads,
                "OpenMP threads per member (default: cores / jobs, at least 1)");
  c->add_flag("--mpi", a->mpi,
              "Run under mpirun: rank 0 hands members to the other ranks as they ask for work");
  c->add_flag("--slurm", a->slurm,
              "Write DIR/sweep.slurm, a job array with one task per member, and stop");
  c->add_option("--member", a->member, "Run only member K (1-based; what a Slurm array task does)");
  c->add_flag("--check", a->check, "Compile every member scene, list the members, and stop");
  c->add_flag("-q,--quiet", a->quiet, "No progress line");
  c->callback([a, &result] { result.exit_code = execute(*a); });
}

}  // namespace fragmpm::pipeline
