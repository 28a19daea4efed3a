// fragmpm: the command line. Each subcommand lives in its own file and registers itself here.
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdlib>

#include "fragmpm/mpm/build_info.hpp"
#include "fragmpm/pipeline/commands.hpp"

namespace {

/// GNU OpenMP reads its wait policy from the environment when the library loads, before main. By
/// default a thread that reaches a barrier spins for up to 300,000 iterations before it sleeps; a
/// step has about five parallel regions, and on a machine whose cores are busy with other work the
/// spinning thread takes the core from the thread it waits for. Measured on 2 cores with two other
/// builds running: 60 steps of the disks peer scene on 2 threads took 17.7 s with the default, 6.4
/// s with GOMP_SPINCOUNT = 10000 and 4.3 s with the passive policy. Unless the user chose a
/// policy, the program re-executes itself once with the passive one (README: "Threads").
void choose_wait_policy(char** argv) {
  if (std::getenv("OMP_WAIT_POLICY") || std::getenv("GOMP_SPINCOUNT")) return;
  if (setenv("OMP_WAIT_POLICY", "passive", 0) != 0) return;
  execv("/proc/self/exe", argv);
  // execv returns only on failure (no /proc): run on with the default policy.
}

}  // namespace

int main(int argc, char** argv) {
  choose_wait_policy(argv);
  CLI::App app{
      "FragMPM: micrograph → grains → DP-MPM crushing simulation → fragment statistics and "
      "figures.\n"
      "Exit codes: 0 success, 2 bad input, 3 numerical failure (last good output kept), 1 other.\n"
      "Threads: OMP_NUM_THREADS or --threads; threads wait passively at barriers unless "
      "OMP_WAIT_POLICY or GOMP_SPINCOUNT is set."};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("fragmpm ") + fragmpm::mpm::program_version() +
                                        " (" + fragmpm::mpm::program_git_hash() + ")");
  fragmpm::pipeline::CommandResult result;
  fragmpm::pipeline::add_run_command(app, result);
  fragmpm::pipeline::add_verify_command(app, result);
  fragmpm::pipeline::add_bench_command(app, result);
  fragmpm::pipeline::add_segment_command(app, result);
  fragmpm::pipeline::add_render_command(app, result);
  fragmpm::pipeline::add_analyze_command(app, result);
  fragmpm::pipeline::add_pipeline_command(app, result);
  fragmpm::pipeline::add_demo_command(app, result);
  fragmpm::pipeline::add_sweep_command(app, result);
  fragmpm::pipeline::add_pool_command(app, result);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return result.exit_code;
}
