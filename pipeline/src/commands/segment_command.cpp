// `fragmpm segment IMAGE --pixel-size 1um [options] -o grains.h5 [--preview preview.png]`
// (docs/design.md): micrograph → grains → particles → grain file and preview.
#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/grain_column.hpp"
#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_file.hpp"
#include "fragmpm/pipeline/segment_particles.hpp"
#include "fragmpm/pipeline/segment_preview.hpp"
#include "fragmpm/pipeline/units.hpp"

namespace fragmpm::pipeline {

namespace {

struct SegmentArguments {
  std::string image;
  std::string pixel_size;
  std::string output;
  std::string preview;
  std::string crop;
  std::string input = "grey";
  bool invert = false;
  std::string denoise = "none";
  int denoise_radius = 2;
  bool equalize = false;
  int gaps = 0;
  double grow = 0.0;
  std::string threshold = "otsu";
  std::optional<double> level;
  int block = 51;
  double offset = 5.0;
  int open = 1;
  int close = 0;
  long long max_hole_area = 100;
  bool no_fill_holes = false;
  bool no_split = false;
  double marker_spacing = 3.0;
  double neck_ratio = 0.65;
  std::vector<int> grain_classes{1};
  std::vector<int> boundary_classes{2};
  std::string boundary_to = "grains";
  long long min_area = 16;
  bool drop_border = false;
  std::vector<double> phase_bands;
  std::string cell_size = "auto";
  int particles_per_cell = 2;
  std::vector<std::string> densities{"2650 kg/m3"};
  bool overwrite = false;
  std::vector<int> stack;  ///< grain labels to stack into a column, bottom first
  std::string stack_area;  ///< total grain area of the column
  int stack_margin = 2;    ///< background pixels around the column
};

cv::Rect parse_crop(const std::string& text) {
  std::vector<int> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    std::size_t used = 0;
    int value = 0;
    try {
      value = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != item.size())
      throw SegmentInputError(fmt::format(
          "--crop '{}': '{}' is not an integer; expected x,y,w,h in pixels", text, item));
    v.push_back(value);
  }
  if (v.size() != 4)
    throw SegmentInputError(
        fmt::format("--crop '{}': expected four integers x,y,w,h in pixels", text));
  return cv::Rect(v[0], v[1], v[2], v[3]);
}

SegmentOptions to_options(const SegmentArguments& a) {
  SegmentOptions o;
  o.image_path = a.image;
  try {
    o.pixel_size = parse_quantity(a.pixel_size, QuantityKind::length);
  } catch (const UnitError& e) {
    throw SegmentInputError(fmt::format("--pixel-size '{}': {}", a.pixel_size, e.what()));
  }
  if (!a.crop.empty()) o.crop = parse_crop(a.crop);
  o.input = a.input == "classes"  ? InputKind::classes
            : a.input == "labels" ? InputKind::labels
                                  : InputKind::grey;
  o.preprocess.invert = a.invert;
  o.preprocess.denoise = a.denoise == "median"      ? DenoiseMethod::median
                         : a.denoise == "gaussian"  ? DenoiseMethod::gaussian
                         : a.denoise == "bilateral" ? DenoiseMethod::bilateral
                                                    : DenoiseMethod::none;
  o.preprocess.denoise_radius = a.denoise_radius;
  o.preprocess.equalize = a.equalize;
  o.preprocess.gap_radius = a.gaps;
  o.grow = a.grow;
  o.threshold.method = a.threshold == "triangle"   ? ThresholdMethod::triangle
                       : a.threshold == "adaptive" ? ThresholdMethod::adaptive
                       : a.threshold == "fixed"    ? ThresholdMethod::fixed
                                                   : ThresholdMethod::otsu;
  if (a.level) {
    if (a.threshold != "fixed" && a.threshold != "otsu")
      throw SegmentInputError(
          fmt::format("--level is the fixed threshold; it cannot be combined with --threshold {}",
                      a.threshold));
    o.threshold.method = ThresholdMethod::fixed;
    o.threshold.level = *a.level;
  } else if (a.threshold == "fixed") {
    throw SegmentInputError(
        "--threshold fixed needs --level (a grey level in the image's own units)");
  }
  o.threshold.adaptive_block = a.block;
  o.threshold.adaptive_offset = a.offset;
  o.cleanup.open_radius = a.open;
  o.cleanup.close_radius = a.close;
  o.cleanup.max_hole_area = a.max_hole_area;
  o.cleanup.fill_holes = !a.no_fill_holes;
  o.split.enabled = !a.no_split;
  o.split.marker_spacing = a.marker_spacing;
  o.split.neck_ratio = a.neck_ratio;
  o.classes.grain_classes = a.grain_classes;
  o.classes.boundary_classes = a.boundary_classes;
  o.classes.boundary_to_grains = a.boundary_to == "grains";
  o.min_area = a.min_area;
  o.drop_border = a.drop_border;
  o.phase_bands = a.phase_bands;
  return o;
}

std::string options_text(const SegmentArguments& a) {
  std::string t = fmt::format(
      "pixel_size = {}\ncrop = {}\ninput = {}\ninvert = {}\ndenoise = {} (radius {})\ngaps = "
      "{}\nequalize = {}\n"
      "threshold = {}{}\nadaptive_block = {}\nadaptive_offset = {}\nopen = {}\nclose = {}\n"
      "max_hole_area = {}\nfill_holes = {}\nsplit = {}\nmarker_spacing = {}\nneck_ratio = {}\n"
      "grain_classes = {}\nboundary_classes = {}\nboundary_to = {}\nmin_area = {}\ndrop_border = "
      "{}\n"
      "grow = {}\nphase_bands = {}\ncell_size = {}\nparticles_per_cell = {}\ndensities = {}\n"
      "stack = {}\nstack_area = {}\nstack_margin = {}\n",
      a.pixel_size, a.crop.empty() ? "none" : a.crop, a.input, a.invert, a.denoise,
      a.denoise_radius, a.gaps, a.equalize, a.threshold,
      a.level ? fmt::format(" (level {})", *a.level) : "", a.block, a.offset, a.open, a.close,
      a.max_hole_area, !a.no_fill_holes, !a.no_split, a.marker_spacing, a.neck_ratio,
      fmt::join(a.grain_classes, ","), fmt::join(a.boundary_classes, ","), a.boundary_to,
      a.min_area, a.drop_border, a.grow, fmt::join(a.phase_bands, ","), a.cell_size,
      a.particles_per_cell, fmt::join(a.densities, ","), fmt::join(a.stack, ","),
      a.stack.empty() ? "none" : a.stack_area, a.stack_margin);
  return t;
}

int execute(const SegmentArguments& a) {
  try {
    const SegmentOptions options = to_options(a);
    // Everything the user typed is checked before the (possibly long) segmentation starts.
    validate_segment_options(options);
    if (a.particles_per_cell < 1)
      throw SegmentInputError(
          fmt::format("--particles-per-cell must be ≥ 1, got {}", a.particles_per_cell));
    std::optional<double> cell_size;
    if (a.cell_size != "auto") {
      try {
        cell_size = parse_quantity(a.cell_size, QuantityKind::length);
      } catch (const UnitError& e) {
        throw SegmentInputError(fmt::format("--cell-size '{}': {}", a.cell_size, e.what()));
      }
      if (!(*cell_size > 0.0))
        throw SegmentInputError(
            fmt::format("--cell-size must be a positive length, got '{}'", a.cell_size));
    }
    std::vector<double> density;
    for (const std::string& d : a.densities) {
      try {
        density.push_back(parse_quantity(d, QuantityKind::density));
      } catch (const UnitError& e) {
        throw SegmentInputError(fmt::format("--density '{}': {}", d, e.what()));
      }
      if (!(density.back() > 0.0))
        throw SegmentInputError(fmt::format("--density must be positive, got '{}'", d));
    }
    const std::size_t phases = options.phase_bands.size() + 1;
    if (density.size() == 1) density.resize(phases, density.front());
    if (density.size() != phases)
      throw SegmentInputError(
          fmt::format("--density: {} value(s) given for {} phase(s) (--phase-bands gives {} band "
                      "limit(s)); give one "
                      "density, or one per phase",
                      a.densities.size(), phases, options.phase_bands.size()));

    std::optional<double> stack_area;
    if (!a.stack.empty()) {
      if (a.stack_area.empty())
        throw SegmentInputError("--stack needs --stack-area (the column's total grain area)");
      try {
        stack_area = parse_quantity(a.stack_area, QuantityKind::area);
      } catch (const UnitError& e) {
        throw SegmentInputError(fmt::format("--stack-area '{}': {}", a.stack_area, e.what()));
      }
      if (!(*stack_area > 0.0))
        throw SegmentInputError(
            fmt::format("--stack-area must be a positive area, got '{}'", a.stack_area));
      if (a.stack_margin < 0)
        throw SegmentInputError(
            fmt::format("--stack-margin must be >= 0 pixels, got {}", a.stack_margin));
    } else if (!a.stack_area.empty()) {
      throw SegmentInputError("--stack-area needs --stack (the grain labels to stack)");
    }

    const Segmentation segmented = segment(options);
    // With --stack the chosen grains are cut out, stacked into a column and rescaled
    // (grain_column.hpp); the column is then read back as a label image so that the grain file
    // describes the column.
    const Segmentation s = [&] {
      if (a.stack.empty()) return segmented;
      for (int label : a.stack)
        if (label < 1 || label > static_cast<int>(segmented.table.grains.size()))
          throw SegmentInputError(fmt::format(
              "--stack: grain {} does not exist; the image has grains 1 … {} (see --preview)",
              label, segmented.table.grains.size()));
      GrainColumn column;
      try {
        column = stack_grains(segmented.table.labels, a.stack, *stack_area, a.stack_margin);
      } catch (const std::invalid_argument& e) {
        throw SegmentInputError(fmt::format("--stack: {}", e.what()));
      }
      SegmentOptions stacked;
      stacked.image_path =
          fmt::format("{} (grains {} stacked)", options.image_path, fmt::join(a.stack, ","));
      stacked.pixel_size = column.pixel_size;
      stacked.input = InputKind::labels;
      stacked.min_area = 1;
      stacked.split.enabled = false;
      return segment(column.labels, stacked);
    }();

    ParticleSampling sampling;
    sampling.particles_per_cell = a.particles_per_cell;
    sampling.cell_size = cell_size ? *cell_size : auto_cell_size(s.table, s.pixel_size);
    const mpm::Particles<2> particles = particles_from_labels(
        s.table.labels, s.pixel_size, sampling, material_of_labels(s.table), density);

    GrainFileExtras extras{sampling, density, options_text(a)};
    write_grain_file(a.output, s, particles, extras, a.overwrite);
    if (!a.preview.empty()) write_preview(draw_preview(s), a.preview);

    std::vector<double> d;
    for (const Grain& g : s.table.grains) d.push_back(g.shape.equivalent_diameter);
    std::sort(d.begin(), d.end());
    std::size_t surface = 0;
    for (const auto flag : particles.surface) surface += flag;
    std::fprintf(
        stderr,
        "fragmpm segment: %s (%d x %d px, window %d,%d,%d,%d)\n"
        "  %zu grains (dropped %lld under %lld px%s), median equivalent diameter %.4g um%s\n"
        "  %zu particles (%zu on surfaces), cell size %.4g um%s, %d per cell per direction -> %s\n",
        s.input.path.c_str(), s.input.full_size.width, s.input.full_size.height, s.input.window.x,
        s.input.window.y, s.input.window.width, s.input.window.height, s.table.grains.size(),
        static_cast<long long>(s.table.dropped_small), a.min_area,
        a.drop_border ? fmt::format(", {} at the border", s.table.dropped_border).c_str() : "",
        1e6 * d[d.size() / 2],
        std::isnan(s.threshold_level)
            ? ""
            : fmt::format(", threshold at {} level {:.5g}", a.gaps > 0 ? "gap-image" : "grey",
                          s.threshold_level)
                  .c_str(),
        particles.size(), surface, 1e6 * sampling.cell_size,
        cell_size ? "" : " (auto: median grain / 8)", sampling.particles_per_cell,
        a.output.c_str());
    if (!a.preview.empty()) std::fprintf(stderr, "  preview -> %s\n", a.preview.c_str());
    return 0;
  } catch (const SegmentInputError& e) {
    std::fprintf(stderr, "fragmpm segment: %s\n", e.what());
    return 2;
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm segment: %s\n", e.what());
    return 2;
  }
}

}  // namespace

void add_segment_command(CLI::App& app, CommandResult& result) {
  auto a = std::make_shared<SegmentArguments>();
  CLI::App* c = app.add_subcommand(
      "segment",
      "Segment a micrograph into grains; write a grain file (labels, grain table, particles)");
  c->add_option("image", a->image,
                "Micrograph (PNG, TIFF 8/16-bit, BMP, JPEG), class mask or label image")
      ->required();
  c->add_option("--pixel-size", a->pixel_size, "Pixel size with unit, e.g. 1um or \"0.5 mm\"")
      ->required();
  c->add_option("-o,--output", a->output, "Grain file to write (HDF5)")->required();
  c->add_option("--preview", a->preview, "PNG with grain outlines and labels drawn over the image");
  c->add_option("--crop", a->crop, "Window x,y,w,h in pixels");
  c->add_option("--input", a->input,
                "grey (micrograph), classes (class mask) or labels (label image)")
      ->check(CLI::IsMember({"grey", "classes", "labels"}))
      ->capture_default_str();
  c->add_flag("--invert", a->invert, "Grains are darker than the background");
  c->add_option("--denoise", a->denoise, "none, median, gaussian or bilateral")
      ->check(CLI::IsMember({"none", "median", "gaussian", "bilateral"}))
      ->capture_default_str();
  c->add_option("--denoise-radius", a->denoise_radius, "Denoising window half-width [px]")
      ->capture_default_str();
  c->add_flag("--equalize", a->equalize, "CLAHE contrast equalisation");
  c->add_option("--gaps", a->gaps,
                "Packed grains of any brightness: dark gaps narrower than about 2x this radius "
                "[px] become background (black top-hat); 0 = off")
      ->capture_default_str();
  c->add_option("--grow", a->grow,
                "After splitting, grains grow into the background by up to this many pixels, never "
                "merging; 0 = off")
      ->capture_default_str();
  c->add_option("--threshold", a->threshold, "otsu, triangle, adaptive or fixed")
      ->check(CLI::IsMember({"otsu", "triangle", "adaptive", "fixed"}))
      ->capture_default_str();
  c->add_option("--level", a->level,
                "Fixed threshold in the image's grey units (implies --threshold fixed)");
  c->add_option("--block", a->block, "Adaptive threshold window [px, odd]")->capture_default_str();
  c->add_option("--offset", a->offset,
                "Adaptive threshold: grain pixels exceed the local mean minus this")
      ->capture_default_str();
  c->add_option("--open", a->open, "Opening radius [px] (removes specks)")->capture_default_str();
  c->add_option("--close", a->close, "Closing radius [px] (fills cracks)")->capture_default_str();
  c->add_option("--max-hole-area", a->max_hole_area,
                "Fill enclosed holes up to this area before splitting [px]")
      ->capture_default_str();
  c->add_flag("--no-fill-holes", a->no_fill_holes, "Keep background enclosed by a single grain");
  c->add_flag("--no-split", a->no_split, "Do not split touching grains");
  c->add_option("--marker-spacing", a->marker_spacing, "Watershed marker radius [px]")
      ->capture_default_str();
  c->add_option("--neck-ratio", a->neck_ratio,
                "Split where the neck is narrower than this fraction of the smaller grain's "
                "inscribed radius")
      ->capture_default_str();
  c->add_option("--grain-class", a->grain_classes, "Class mask values that are grain")
      ->delimiter(',')
      ->capture_default_str();
  c->add_option("--boundary-class", a->boundary_classes,
                "Class mask values that are grain boundaries")
      ->delimiter(',')
      ->capture_default_str();
  c->add_option("--boundary-to", a->boundary_to,
                "Boundary pixels join the nearest grain, or the background")
      ->check(CLI::IsMember({"grains", "background"}))
      ->capture_default_str();
  c->add_option("--min-area", a->min_area, "Drop grains with fewer pixels")->capture_default_str();
  c->add_flag("--drop-border", a->drop_border, "Drop grains cut by the image (window) border");
  c->add_option("--phase-bands", a->phase_bands,
                "Grey-level limits between phases (material ids), ascending")
      ->delimiter(',');
  c->add_option("--cell-size", a->cell_size,
                "Grid cell size h for the particles, e.g. 10um (auto: median grain / 8)")
      ->capture_default_str();
  c->add_option("--particles-per-cell", a->particles_per_cell, "Particles per cell per direction")
      ->capture_default_str();
  c->add_option("--density", a->densities,
                "Density per phase, e.g. \"2650 kg/m3\" (one value = all phases)")
      ->delimiter(',')
      ->capture_default_str();
  c->add_flag("--overwrite", a->overwrite, "Replace an existing grain file");
  c->add_option("--stack", a->stack,
                "Grain labels (as in --preview) to stack into a touching column, bottom first; "
                "the grain file then holds the column")
      ->delimiter(',');
  c->add_option("--stack-area", a->stack_area,
                "Total grain area of the stacked column, e.g. \"94 mm2\" (sets the pixel size)");
  c->add_option("--stack-margin", a->stack_margin, "Background pixels around the stacked column")
      ->capture_default_str();
  c->callback([a, &result] { result.exit_code = execute(*a); });
}

}  // namespace fragmpm::pipeline
