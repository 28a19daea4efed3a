// `fragmpm render RUN.h5 --field damage|temperature|speed|stress|body|fragment [--frame N|last] -o
// fig.png` and `fragmpm render RUN.h5 --series energy|force-displacement -o fig.png`
// (docs/design.md): off-screen figures of one frame or of the run's /series, with no display
// needed.
#include <fmt/format.h>

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fragmpm/analysis/figure_error.hpp"
#include "fragmpm/analysis/frame_figure.hpp"
#include "fragmpm/analysis/particle_figure.hpp"
#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/analysis/series_figures.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"
#include "fragmpm/pipeline/commands.hpp"

namespace fragmpm::pipeline {

namespace {

struct RenderArguments {
  std::string run;
  std::string field;
  std::string series;
  std::string frame = "last";
  bool frame_given = false;
  std::string output;
  int width = 1200;
  int height = 900;
  bool overwrite = false;
};

/// Bad command-line input: reported with the command's name, exit code 2.
struct RenderInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

int frame_index(const std::string& text, int frame_count, const std::string& run) {
  if (frame_count == 0) throw RenderInputError(fmt::format("{}: the run has no frames yet", run));
  if (text == "last") return frame_count - 1;
  std::size_t used = 0;
  long long index = -1;
  try {
    index = std::stoll(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size())
    throw RenderInputError(fmt::format("--frame '{}': expected a frame number or 'last'", text));
  if (index < 0 || index >= frame_count)
    throw RenderInputError(
        fmt::format("--frame {}: {} has frames 0 to {}", text, run, frame_count - 1));
  return static_cast<int>(index);
}

/// Frame datasets the figure of `field` needs besides x (read_frame fills absent ones with
/// defaults, which would draw a plausible but wrong figure).
std::vector<std::string> required_datasets(analysis::FrameField field) {
  switch (field) {
    case analysis::FrameField::damage:
      return {"r1", "r2", "damage"};
    case analysis::FrameField::temperature:
      return {"r1", "r2", "temperature"};
    case analysis::FrameField::speed:
      return {"r1", "r2", "v"};
    case analysis::FrameField::stress:
      return {"r1", "r2", "stress"};
    case analysis::FrameField::body:
      return {"r1", "r2", "body"};
  }
  return {};
}

constexpr const char* fragment_field = "fragment";

void require_datasets(const mpm::RunFileReader& file, int index,
                      const std::vector<std::string>& names, const RenderArguments& a) {
  char group[32];
  std::snprintf(group, sizeof group, "frames/%06d", index);
  const mpm::FrameEntry* frame = file.find_frame(index);
  for (const std::string& name : names)
    if (!frame || !frame->has(name))
      throw RenderInputError(
          fmt::format("{}: /{}/{}: not stored in this frame, so the {} figure cannot be "
                      "drawn (the scene's output fields decide what frames keep)",
                      a.run, group, name, a.field));
}

void render_field(const RenderArguments& a) {
  // Fragments are labelled as `fragmpm analyze` does with its default options (docs/design.md):
  // frame 0 is the reference configuration whose neighbours may stay bonded.
  const bool fragments = a.field == fragment_field;
  const analysis::FrameField field =
      fragments ? analysis::FrameField::damage : analysis::parse_frame_field(a.field);
  int index = 0;
  double time = 0.0;
  long long step = 0;
  mpm::Particles<2> particles, reference;
  {
    const mpm::RunFileReader file = mpm::RunFileReader::open(a.run);
    index = frame_index(a.frame, static_cast<int>(file.frames().size()), a.run);
    const std::vector<std::string> fragment_data{"r1", "r2", "damage", "body"};
    require_datasets(file, index, fragments ? fragment_data : required_datasets(field), a);
    if (fragments) require_datasets(file, 0, fragment_data, a);
    particles = file.read_frame<2>(index, &time, &step);
    if (fragments) reference = index == 0 ? particles : file.read_frame<2>(0);
  }
  const std::string title = fmt::format("{} - frame {} (step {}) of {}", a.field, index, step,
                                        std::filesystem::path(a.run).filename().string());
  analysis::ParticleFigure figure;
  if (fragments) {
    if (reference.size() != particles.size())
      throw RenderInputError(
          fmt::format("{}: frame {} has {} particles but the reference frame 0 has {}", a.run,
                      index, particles.size(), reference.size()));
    const analysis::FragmentLabels labels = analysis::label_fragments(reference, particles);
    figure = analysis::fragment_figure(
        particles, analysis::resolved_fragment_ids(labels), time,
        fmt::format("{} fragments - frame {} (step {}) of {}", labels.resolved(), index, step,
                    std::filesystem::path(a.run).filename().string()));
  } else {
    figure = analysis::frame_figure(particles, field, time, title);
  }
  figure.width = a.width;
  figure.height = a.height;
  analysis::write_particle_figure(figure, a.output);
  std::fprintf(stderr, "fragmpm render: %s of frame %d (t = %.6g s, %zu particles) -> %s\n",
               a.field.c_str(), index, time, particles.size(), a.output.c_str());
}

void render_series(const RenderArguments& a) {
  analysis::PlotSpec spec;
  if (a.series == "energy") {
    if (!std::filesystem::exists(a.run)) throw RenderInputError(a.run + ": no such file");
    spec = analysis::energy_plot_spec(mpm::RunFileReader::open(a.run).read_series());
  } else if (a.series == "force-displacement") {
    const mpm::RunFileReader file = mpm::RunFileReader::open(a.run);
    spec = analysis::force_displacement_spec(file.read_series(), file.meta().wall_names);
  } else {
    throw RenderInputError(
        fmt::format("--series '{}': expected energy or force-displacement", a.series));
  }
  spec.width = a.width;
  spec.height = a.height;
  analysis::write_line_plot(spec, a.output);
  std::fprintf(stderr, "fragmpm render: %s series -> %s\n", a.series.c_str(), a.output.c_str());
}

int execute(const RenderArguments& a) {
  try {
    if (a.field.empty() == a.series.empty())
      throw RenderInputError(
          "give either --field (a frame figure) or --series (a plot over time), not both");
    if (!a.series.empty() && a.frame_given)
      throw RenderInputError(
          "--frame applies to --field figures; --series plots cover the whole run");
    if (!a.field.empty() && a.field != fragment_field) try {
        analysis::parse_frame_field(a.field);  // fail before touching any file
      } catch (const analysis::FigureError& e) {
        throw RenderInputError(std::string(e.what()) + " or fragment");
      }
    std::string extension = std::filesystem::path(a.output).extension().string();
    for (char& c : extension) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    if (extension != ".png")
      throw RenderInputError(
          fmt::format("-o {}: figures are PNG; expected a path ending in .png", a.output));
    if (std::filesystem::exists(a.output) && !a.overwrite)
      throw RenderInputError(fmt::format("{} exists; pass --overwrite to replace it", a.output));
    if (!std::filesystem::exists(a.run)) throw RenderInputError(a.run + ": no such file");
    if (a.field.empty())
      render_series(a);
    else
      render_field(a);
    return 0;
  } catch (const RenderInputError& e) {
    std::fprintf(stderr, "fragmpm render: %s\n", e.what());
  } catch (const analysis::FigureError& e) {
    std::fprintf(stderr, "fragmpm render: %s\n", e.what());
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm render: %s\n", e.what());
  } catch (const std::invalid_argument& e) {  // label_fragments: frame data it cannot label
    std::fprintf(stderr, "fragmpm render: %s: %s\n", a.run.c_str(), e.what());
  }
  return 2;
}

}  // namespace

void add_render_command(CLI::App& app, CommandResult& result) {
  auto args = std::make_shared<RenderArguments>();
  CLI::App* render = app.add_subcommand(
      "render",
      "Draw a figure of a run file as PNG, off-screen: a frame's particles coloured by a field, "
      "or the energy balance / force-displacement over the run");
  render->add_option("run", args->run, "Run file (HDF5) written by `fragmpm run`")->required();
  render->add_option("--field", args->field,
                     "Frame figure: damage, temperature, speed, stress, body or fragment (labelled "
                     "as analyze does)");
  render->add_option("--series", args->series, "Plot over the run: energy or force-displacement");
  render->add_option("--frame", args->frame, "Frame number, or 'last' (default)")
      ->each([args](const std::string&) { args->frame_given = true; });
  render->add_option("-o,--output", args->output, "PNG file to write")->required();
  render->add_option("--width", args->width, "Figure width in pixels (default 1200)")
      ->check(CLI::Range(200, 16384));
  render->add_option("--height", args->height, "Figure height in pixels (default 900)")
      ->check(CLI::Range(200, 16384));
  render->add_flag("--overwrite", args->overwrite, "Replace an existing PNG");
  render->callback([args, &result] { result.exit_code = execute(*args); });
}

}  // namespace fragmpm::pipeline
