#pragma once
// Subcommands of `fragmpm`. Each add_*_command registers its CLI11 subcommand; its callback runs
// the command and stores the process exit code in `result` (0 ok, 2 bad input, 3 numerical failure,
// 1 anything else).
#include <CLI/CLI.hpp>

namespace fragmpm::pipeline {

struct CommandResult {
  int exit_code = 0;
};

void add_run_command(CLI::App& app, CommandResult& result);
void add_verify_command(CLI::App& app, CommandResult& result);
void add_bench_command(CLI::App& app, CommandResult& result);
void add_segment_command(CLI::App& app, CommandResult& result);
void add_render_command(CLI::App& app, CommandResult& result);
void add_analyze_command(CLI::App& app, CommandResult& result);
void add_pipeline_command(CLI::App& app, CommandResult& result);
void add_demo_command(CLI::App& app, CommandResult& result);
void add_sweep_command(CLI::App& app, CommandResult& result);
void add_pool_command(CLI::App& app, CommandResult& result);

}  // namespace fragmpm::pipeline
