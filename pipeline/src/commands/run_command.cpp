// `fragmpm run SCENE.toml [-o RUN.h5]` and `fragmpm run --restart RUN.h5`.
#include <omp.h>

#include <cstdio>
#include <filesystem>
#include <iostream>

#include "fragmpm/mpm/state_extremes.hpp"
#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/run_loop.hpp"
#include "fragmpm/pipeline/scene.hpp"

namespace fragmpm::pipeline {

namespace {

struct RunArguments {
  std::string scene;
  std::string output;
  std::string restart;
  int threads = 0;
  long long max_steps = 0;
  bool overwrite = false;
  bool quiet = false;
};

void log_modules(const std::vector<mpm::ModuleDecision>& modules) {
  for (const auto& m : modules)
    std::fprintf(stderr, "  module %-13s %-3s  %s\n", m.module.c_str(), m.active ? "on" : "off",
                 m.reason.c_str());
}

int execute(const RunArguments& args) {
  if (args.threads > 0) omp_set_num_threads(args.threads);
  try {
    mpm::Problem<2> problem;
    std::optional<mpm::Checkpoint<2>> checkpoint;
    std::optional<mpm::RunFile<2>> file;
    if (!args.restart.empty()) {
      file.emplace(mpm::RunFile<2>::open_existing(args.restart));
      const mpm::RunMeta meta = file->meta();
      problem = parse_scene(meta.scene_text, meta.scene_path);
      checkpoint = file->read_checkpoint();
      if (!checkpoint) {
        std::fprintf(stderr, "fragmpm run: %s has no /checkpoint to restart from\n",
                     args.restart.c_str());
        return 2;
      }
      file->truncate_after(checkpoint->step);
      std::fprintf(stderr, "fragmpm: restarting %s from step %lld, t = %.6g s\n",
                   args.restart.c_str(), checkpoint->step, checkpoint->time);
    } else {
      if (args.scene.empty()) {
        std::fprintf(stderr, "fragmpm run: give a SCENE.toml, or --restart RUN.h5\n");
        return 2;
      }
      problem = load_scene(args.scene);
      std::string output = args.output;
      if (output.empty())
        output = std::filesystem::path(args.scene).filename().replace_extension(".h5").string();
      file.emplace(mpm::RunFile<2>::create(output, run_meta(problem), args.overwrite));
    }
    const auto modules = mpm::plan_modules<2>(problem);
    std::fprintf(stderr,
                 "fragmpm: %zu particles, %zu bodies, %zu walls, cell size %.4g m, %d thread(s)\n",
                 problem.particles.size(), problem.body_names.size(), problem.walls.size(),
                 problem.grid.cell_size, omp_get_max_threads());
    log_modules(modules);
    std::fprintf(stderr, "  particles that leave the domain %s\n",
                 problem.grid.outside == mpm::OutsidePolicy::remove
                     ? "are removed ([grid] outside = \"remove\"; booked in /series lost_*)"
                     : "stop the run ([grid] outside = \"stop\")");
    mpm::Solver<2> solver(std::move(problem));
    if (checkpoint)
      solver.restore(checkpoint->time, checkpoint->step, checkpoint->totals,
                     std::move(checkpoint->particles), std::move(checkpoint->phase_field));
    RunLoopOptions options;
    options.write_initial_frame = !checkpoint.has_value();
    options.progress = !args.quiet;
    if (args.max_steps > 0) options.max_steps_override = args.max_steps;
    const RunLoopResult result = run_loop(solver, *file, options);
    const auto& row = solver.last_row();
    if (result.failed) {
      std::fprintf(stderr,
                   "fragmpm: numerical failure at step %lld, t = %.6g s:\n  %s\n"
                   "  the frames written before it are kept in %s\n",
                   result.failure.step, result.failure.time, result.failure.what.c_str(),
                   file->path().c_str());
      return 3;
    }
    const double scale = std::max(mpm::energy_input(row), 1e-300);
    std::fprintf(
        stderr,
        "fragmpm: done, %lld steps to t = %.6g s in %.2f s (%.3g particle-steps/s), %d frames "
        "-> %s\n  energy [J/m]: kinetic %.6g, strain %.6g, wall work %.6g, gravity work %.6g, "
        "load work %.6g, damage dissipation %.6g, crushed flow %.6g, crack energy (phase field) "
        "%.6g, history excess (phase field, put in) %.6g, friction %.6g, "
        "contact %.6g, transfer %.6g, "
        "balance error %.3g "
        "(%.2g %% of input)\n",
        result.steps, solver.time(), result.wall_seconds,
        result.wall_seconds > 0
            ? double(result.steps) * double(solver.particles().size()) / result.wall_seconds
            : 0.0,
        result.frames, file->path().c_str(), row.kinetic, row.strain, row.totals.wall_work,
        row.totals.gravity_work, row.totals.load_work, row.totals.dissipated,
        row.totals.flow_dissipation, row.totals.fracture_energy, row.totals.history_excess,
        row.totals.friction_work, row.totals.contact_dissipation, row.totals.transfer_dissipation,
        row.balance_error, 100.0 * std::abs(row.balance_error) / scale);
    // From the finished state, outside the step: J = det F far above 1 marks failed material
    // spreading out, a principal stress far above the strengths an unstable step.
    std::fprintf(stderr, "  end state: %s\n",
                 mpm::describe(mpm::state_extremes<2>(solver.particles())).c_str());
    // The phase-field stage's share of this invocation's wall time (a restarted run counts from
    // the restart): where a long run spends its time once cracks are open.
    const mpm::PhaseFieldWork& work = solver.phase_field_work();
    if (work.runs > 0)
      std::fprintf(stderr,
                   "  phase field: %lld solves, %lld of them direct (sparse LDLT, %lld with the "
                   "last step's ordering; %lld runs of them after conjugate gradients passed "
                   "%d iterations and the cost of a factorisation), %lld past %d iterations and "
                   "converged (a factorisation weighed at up to %.0f iterations), %lld "
                   "preconditioned by multigrid (%lld with levels kept from an earlier step), %.1f "
                   "conjugate-gradient iterations a solve, %.1f s (%.0f %% of the run)\n",
                   work.runs, work.direct_runs, work.reused_orderings, work.stopped_at_limit,
                   mpm::phase_field_iteration_limit, work.past_limit,
                   mpm::phase_field_iteration_limit, work.factorisation_iterations,
                   work.multigrid_solves, work.kept_levels,
                   double(work.iterations) / double(work.runs), work.seconds,
                   result.wall_seconds > 0 ? 100.0 * work.seconds / result.wall_seconds : 0.0);
    const mpm::LostParticles& lost = row.totals.lost;
    if (solver.problem().grid.outside == mpm::OutsidePolicy::remove)
      std::fprintf(stderr,
                   "  left the domain and removed: %lld particles, mass %.6g kg/m, kinetic %.6g "
                   "J/m, strain %.6g J/m (in the balance above)\n",
                   lost.count, lost.mass, lost.kinetic, lost.strain);
    return 0;
  } catch (const SceneError& e) {
    std::fprintf(stderr, "fragmpm run: %s\n", e.what());
    return 2;
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm run: %s\n", e.what());
    return 2;
  }
}

}  // namespace

void add_run_command(CLI::App& app, CommandResult& result) {
  auto args = std::make_shared<RunArguments>();
  CLI::App* run =
      app.add_subcommand("run", "Simulate a scene file and write a run file (HDF5 + XDMF)");
  run->add_option("scene", args->scene, "Scene file (TOML, see scenes/README.md)");
  run->add_option("-o,--output", args->output, "Run file to write (default: SCENE stem + .h5)");
  run->add_option("--restart", args->restart, "Continue RUN.h5 from its last checkpoint");
  run->add_option("--threads", args->threads, "OpenMP threads (default: all cores)");
  run->add_option("--max-steps", args->max_steps,
                  "Stop after this many steps (the run can be continued with --restart)");
  run->add_flag("--overwrite", args->overwrite, "Replace an existing run file");
  run->add_flag("-q,--quiet", args->quiet, "No progress line");
  run->callback([args, &result] { result.exit_code = execute(*args); });
}

}  // namespace fragmpm::pipeline
