// `fragmpm demo [-o DIR] [--small]`: the pipeline on the embedded scene
// scenes/demo/sandstone-pack.toml (73 grains; --small: the 8 grains of
// scenes/demo/sandstone-crush.toml) and the Miocene sandstone grain mask. The scene is compiled
// into the program; the image is found on disk, first under $FRAGMPM_SOURCE_DIR/images, then in an
// images/ folder beside the executable or any folder above it (./build/fragmpm of a clone finds
// <clone>/images), then in the working directory or any folder above it.
#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>

#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/pipeline_job.hpp"
#include "fragmpm/pipeline/source_file.hpp"

namespace fragmpm::pipeline {

namespace fs = std::filesystem;

namespace {

constexpr const char* demo_scene = "demo/sandstone-pack.toml";
constexpr const char* small_demo_scene = "demo/sandstone-crush.toml";
constexpr const char* demo_image = "images/miocene_sandstone_pack.png";
constexpr const char* small_demo_image = "images/miocene_sandstone_window.png";

struct DemoArguments {
  std::string output = "fragmpm-demo";
  bool overwrite = false;
  int threads = 0;
  bool quiet = false;
  bool small = false;
};

int execute(const DemoArguments& a) {
  try {
    PipelineOptions o;
    o.image = find_source_file(a.small ? small_demo_image : demo_image, "the demo's micrograph");
    const char* scene = a.small ? small_demo_scene : demo_scene;
    o.scene_text = embedded_scene(scene);
    o.scene_path = std::string("scenes/") + scene;
    o.output_dir = a.output;
    o.overwrite = a.overwrite;
    o.threads = a.threads;
    o.progress = !a.quiet;
    std::fprintf(stderr, "fragmpm demo: %s (embedded) on %s -> %s/\n", o.scene_path.c_str(),
                 o.image.c_str(), a.output.c_str());
    const PipelineResult r = run_pipeline(o, stderr);
    const fs::path dir(a.output);
    std::printf("fragmpm demo: everything is in %s/\n", a.output.c_str());
    std::printf("  open this first        %s\n", (dir / "report.html").string().c_str());
    std::printf("  segmentation preview   %s\n", (dir / "segmentation.png").string().c_str());
    std::printf("  run file (+ XDMF)      %s (%s)\n", r.run_path.c_str(),
                (dir / "run.xmf").string().c_str());
    std::printf("  fragment tables, CDFs  %s/\n", (dir / "fragments").string().c_str());
    std::printf("  field and series figs  %s/\n", (dir / "figures").string().c_str());
    std::printf("  summary                %s\n\n%s", r.summary_path.c_str(), r.summary.c_str());
    return r.exit_code;
  } catch (const PipelineError& e) {
    std::fprintf(stderr, "fragmpm demo: %s\n", e.what());
    return 2;
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm demo: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "fragmpm demo: %s\n", e.what());
    return 1;
  }
}

}  // namespace

void add_demo_command(CLI::App& app, CommandResult& result) {
  auto args = std::make_shared<DemoArguments>();
  CLI::App* cmd = app.add_subcommand("demo",
                                     "The main job on built-in data: the 73 grains of a sandstone "
                                     "grain mask (1000 x 750 um) crushed between platens with "
                                     "frictional and damage heating; segmentation preview, run "
                                     "file, fragment tables, figures, summary and report.html (the "
                                     "pipeline command). A few minutes on 2 cores");
  cmd->add_option("-o,--output", args->output, "Output directory (default: fragmpm-demo)");
  cmd->add_flag("--overwrite", args->overwrite, "Write into an existing non-empty directory");
  cmd->add_option("--threads", args->threads, "OpenMP threads (default: all cores)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress line");
  cmd->add_flag("--small", args->small,
                "A quick look instead: 8 grains of a 200 x 150 um window, isothermal (about a "
                "minute)");
  cmd->callback([args, &result] { result.exit_code = execute(*args); });
}

}  // namespace fragmpm::pipeline
