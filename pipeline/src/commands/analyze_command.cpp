// `fragmpm analyze RUN.h5 [--at TIMES|--at-displacement DISPLACEMENTS] [--frame N] [--platen NAME]
// [-o DIR] [--d-mask 0.99] [--min-particles 4] [--body N]` (docs/design.md). The work is
// analyze_run.
#include <cstdio>
#include <memory>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/pipeline/analyze.hpp"
#include "fragmpm/pipeline/commands.hpp"

namespace fragmpm::pipeline {

namespace {

struct AnalyzeArguments {
  AnalyzeOptions options;
  bool csv_only = false;
  bool no_figures = false;
};

int execute(AnalyzeArguments a) {
  a.options.write_run_file = !a.csv_only;
  a.options.figures = !a.no_figures;
  try {
    analyze_run(a.options, stderr);
    return 0;
  } catch (const AnalyzeError& e) {
    std::fprintf(stderr, "fragmpm analyze: %s\n", e.what());
    return 2;
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm analyze: %s\n", e.what());
    return 2;
  }
}

}  // namespace

void add_analyze_command(CLI::App& app, CommandResult& result) {
  auto a = std::make_shared<AnalyzeArguments>();
  AnalyzeOptions& o = a->options;
  CLI::App* c = app.add_subcommand("analyze",
                                   "Fragments of a run: tables (CSV and /fragments/ in the run "
                                   "file), size and roundness CDFs, count and mean "
                                   "size against time, figures");
  c->add_option("run", o.run_path, "Run file (HDF5) written by fragmpm run")->required();
  c->add_option("--at", o.at,
                "Frames nearest to these times (\"20us,50us\") or platen displacements "
                "(\"0.2mm,0.8mm\"); a unit "
                "is required. Default: the frames at 25, 50, 75 and 100 % of the run")
      ->delimiter(',');
  c->add_option(
       "--at-displacement", o.at_displacement,
       "Frames nearest to these platen displacements (\"0.2mm,0.8mm\"; a bare number is metres)")
      ->delimiter(',');
  c->add_option("--frame", o.frames, "Frame indices, or first / last")->delimiter(',');
  c->add_option("--platen", o.platen,
                "Wall whose displacement is the platen travel (default: the only moving wall)");
  c->add_option(
      "-o,--output", o.output_dir,
      "Directory for CSV tables and figures (default: RUN_fragments/ beside the run file)");
  CLI::Option* mask =
      c->add_option("--d-mask", o.fragments.d_mask,
                    "Particles with damage d >= this belong to no fragment (a run with the phase "
                    "field: 0.9 unless given)")
          ->capture_default_str();
  c->add_option("--min-particles", o.fragments.min_particles,
                "Fragments with fewer particles are reported as fines (4 = one cell at 2 x 2 "
                "particles per cell)")
      ->capture_default_str();
  c->add_option("--body", o.body,
                "Analyse only this body's particles: its index in the frames' 'body' field (the "
                "order of the scene's bodies and grains). Default: all bodies")
      ->check(CLI::NonNegativeNumber);
  c->add_flag("--csv-only", a->csv_only, "Do not write /fragments/ groups into the run file");
  c->add_flag("--no-figures", a->no_figures, "Do not write the PNG figures");
  c->callback([a, mask, &result] {
    a->options.d_mask_given = mask->count() > 0;
    result.exit_code = execute(*a);
  });
}

}  // namespace fragmpm::pipeline
