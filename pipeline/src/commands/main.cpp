// fragmpm: the command line. Each subcommand lives in its own file and registers itself here.
#include <CLI/CLI.hpp>

#include "fragmpm/mpm/build_info.hpp"
#include "fragmpm/pipeline/commands.hpp"

int main(int argc, char** argv) {
  CLI::App app{
      "FragMPM: micrograph → grains → DP-MPM crushing simulation → fragment statistics and "
      "figures.\n"
      "Exit codes: 0 success, 2 bad input, 3 numerical failure (last good output kept), 1 other."};
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
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 2;
  }
  return result.exit_code;
}
