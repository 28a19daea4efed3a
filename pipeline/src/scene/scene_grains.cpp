// [[bodies]] from a micrograph or a grain file: segmentation options from the entry's keys, grains
// sampled at the scene's cell size, every grain its own body (scenes/README.md).
#include "scene_grains.hpp"

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <limits>

#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/segment.hpp"

namespace fragmpm::pipeline::scene_detail {
namespace {

using QK = QuantityKind;

/// [a, b, …] of integers in [lo, hi].
std::vector<long long> integer_list(const Section& s, std::string_view k, long long lo,
                                    long long hi, const std::string& what) {
  const toml::array* a = s.find(k)->as_array();
  if (!a) s.expected(k, "an array of " + what);
  std::vector<long long> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node* e = a->get(i);
    if (!e->is_integer() || e->as_integer()->get() < lo || e->as_integer()->get() > hi)
      fail(s.file(), static_cast<int>(e->source().begin.line),
           s.key(std::string(k) + "[" + std::to_string(i) + "]"),
           "expected " + what + ", got " + describe(*e));
    out.push_back(e->as_integer()->get());
  }
  return out;
}

/// `path` relative to the scene file's directory unless absolute.
std::string resolve(const std::string& path, const std::string& scene_path) {
  const std::filesystem::path p(path);
  if (p.is_absolute()) return path;
  return (std::filesystem::path(scene_path).parent_path() / p).lexically_normal().string();
}

}  // namespace

SegmentOptions read_segment_options(const Section& b, const std::string& image_path) {
  SegmentOptions o;
  o.image_path = image_path;
  o.pixel_size = b.quantity("pixel_size", QK::length);
  if (!(o.pixel_size > 0.0))
    b.expected("pixel_size", "a positive length (the size of one pixel, e.g. \"1 um\")");
  if (auto in = b.optional_string("input")) {
    if (*in == "grey")
      o.input = InputKind::grey;
    else if (*in == "classes")
      o.input = InputKind::classes;
    else if (*in == "labels")
      o.input = InputKind::labels;
    else
      b.expected("input", "one of \"grey\", \"classes\", \"labels\"");
  }
  if (b.has("crop")) {
    const auto c =
        integer_list(b, "crop", 0, std::numeric_limits<int>::max(), "pixel integers >= 0");
    if (c.size() != 4 || c[2] < 1 || c[3] < 1)
      b.expected("crop", "a window [x, y, w, h] in pixels with w, h >= 1");
    o.crop = cv::Rect(static_cast<int>(c[0]), static_cast<int>(c[1]), static_cast<int>(c[2]),
                      static_cast<int>(c[3]));
  }
  if (const toml::node* t = b.find("threshold")) {
    if (t->is_number()) {
      o.threshold.method = ThresholdMethod::fixed;
      o.threshold.level = b.number("threshold");
    } else {
      const std::string m = b.string("threshold");
      if (m == "otsu")
        o.threshold.method = ThresholdMethod::otsu;
      else if (m == "triangle")
        o.threshold.method = ThresholdMethod::triangle;
      else if (m == "adaptive")
        o.threshold.method = ThresholdMethod::adaptive;
      else
        b.expected("threshold", "\"otsu\", \"triangle\", \"adaptive\" or a grey level (number)");
    }
  }
  o.preprocess.invert = b.optional_bool("invert").value_or(false);
  o.split.enabled = b.optional_bool("split").value_or(true);
  o.drop_border = b.optional_bool("drop_border").value_or(false);
  if (auto a = b.optional_integer("min_area")) {
    if (*a < 1) b.expected("min_area", "a grain area in pixels >= 1");
    o.min_area = *a;
  }
  auto classes = [&](std::string_view k, std::vector<int>& dst) {
    if (!b.has(k)) return;
    if (o.input != InputKind::classes)
      b.fail(k, "expected " + std::string(k) + " only with input = \"classes\"");
    dst.clear();
    for (long long v : integer_list(b, k, 0, 65535, "class values 0 … 65535"))
      dst.push_back(static_cast<int>(v));
  };
  classes("grain_classes", o.classes.grain_classes);
  classes("boundary_classes", o.classes.boundary_classes);
  return o;
}

namespace {

/// The key an error of the segmentation is about.
std::string_view key_of_segment_error(const Section& b, const std::string& message) {
  if (b.has("crop") && message.find("crop") != std::string::npos) return "crop";
  return "image";
}

}  // namespace

bool is_grain_source(const Section& body) {
  return body.has("image") || body.has("grains");
}

GrainEntry read_grain_entry(const Section& b, const std::string& scene_path, int material,
                            const mpm::MaterialSpec& spec, const mpm::GridSpec<2>& grid,
                            int per_cell) {
  GrainEntry e{b.name("name"), b, {}, {}};
  const ParticleSampling sampling{grid.cell_size, per_cell};
  const bool from_image = b.has("image");
  if (from_image && b.has("grains")) b.fail("grains", "expected either image or grains, got both");
  if (b.has("shape"))
    b.fail("shape", "expected no shape for a body from " +
                        std::string(from_image ? "an image" : "a grain file"));
  const std::string source_key = from_image ? "image" : "grains";
  const std::string source = resolve(b.string(source_key), scene_path);
  // Every phase of the image gets the entry's material (one material per entry).
  std::vector<double> density;
  try {
    if (from_image) {
      b.allow_only({"name", "material", "image", "pixel_size", "origin", "velocity", "input",
                    "crop", "threshold", "invert", "split", "drop_border", "min_area",
                    "grain_classes", "boundary_classes", "temperature"});
      const SegmentOptions options = read_segment_options(b, source);
      density.assign(options.phase_bands.size() + 1, spec.density);
      e.bodies = grain_bodies_from_image(options, sampling, density);
    } else {
      b.allow_only({"name", "material", "grains", "origin", "velocity", "temperature"});
      density.assign(256, spec.density);
      e.bodies = grain_bodies_from_file(source, sampling, density);
    }
  } catch (const SegmentInputError& err) {
    b.fail(from_image ? key_of_segment_error(b, err.what()) : source_key,
           std::string("expected a usable ") + (from_image ? "image" : "grain file") +
               ", got: " + err.what());
  } catch (const mpm::RunFileError& err) {
    b.fail(source_key, std::string("expected a readable grain file, got: ") + err.what());
  }

  // Grains too small for one lattice point have no particles: drop them so every body has some.
  mpm::Particles<2>& P = e.bodies.particles;
  const std::size_t n_grains = e.bodies.grains.size();
  std::vector<std::size_t> count(n_grains, 0);
  for (std::int32_t id : P.body) ++count[static_cast<std::size_t>(id)];
  std::vector<std::int32_t> new_id(n_grains, -1);
  std::vector<Grain> kept;
  for (std::size_t k = 0; k < n_grains; ++k) {
    if (count[k] == 0) continue;
    new_id[k] = static_cast<std::int32_t>(kept.size());
    kept.push_back(e.bodies.grains[k]);
    e.body_names.push_back(e.name + "-grain-" + std::to_string(e.bodies.grains[k].label));
  }
  if (kept.empty())
    b.fail(source_key,
           "expected grains that hold at least one particle at cell_size / particles_per_cell = " +
               si(grid.cell_size / per_cell, "m") + ", got " + std::to_string(n_grains) +
               " grain(s) and no particle");
  if (kept.size() < n_grains)
    std::cerr << b.file() << ":" << b.line() << ": warning: body '" << e.name
              << "': " << n_grains - kept.size() << " grain(s) smaller than the particle spacing "
              << si(grid.cell_size / per_cell, "m") << " hold no particle and are left out\n";
  e.bodies.grains = std::move(kept);

  // Place: the window's lower-left corner lands on `origin` (image rows run down, y runs up).
  const Vec2 origin = b.optional_vector("origin", QK::length).value_or(Vec2::Zero());
  const Vec2 velocity = b.optional_vector("velocity", QK::velocity).value_or(Vec2::Zero());
  const double half = 0.5 * grid.cell_size / per_cell;
  double worst = 0.0;
  std::string where;
  static const char* axis[2] = {"x", "y"};
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.x[p] += origin;
    P.v[p] = velocity;
    P.body[p] = new_id[static_cast<std::size_t>(P.body[p])];
    P.material[p] = material;
    P.strength[p] = std::numeric_limits<double>::infinity();  // as shape bodies: no damage law yet
    for (int d = 0; d < 2; ++d) {
      if (grid.min[d] - (P.x[p][d] - half) > worst) {
        worst = grid.min[d] - (P.x[p][d] - half);
        where = "below grid.min in " + std::string(axis[d]);
      }
      if ((P.x[p][d] + half) - grid.max[d] > worst) {
        worst = (P.x[p][d] + half) - grid.max[d];
        where = "above grid.max in " + std::string(axis[d]);
      }
    }
  }
  if (worst > 1e-9 * grid.cell_size)
    b.fail(b.has("origin") ? "origin" : source_key,
           "expected the grains of '" + e.name +
               "' inside the grid domain [grid.min, grid.max], got grains extending " +
               si(worst, "m") + " " + where + " (window " + si(e.bodies.width, "m") + " x " +
               si(e.bodies.height, "m") + " with its lower-left corner at [" + si(origin.x(), "m") +
               ", " + si(origin.y(), "m") + "])");
  return e;
}

}  // namespace fragmpm::pipeline::scene_detail
