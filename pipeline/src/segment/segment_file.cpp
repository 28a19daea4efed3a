#include "fragmpm/pipeline/segment_file.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdint>
#include <sstream>

#include "fragmpm/mpm/build_info.hpp"
#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/mpm/run_file.hpp"

namespace fragmpm::pipeline {

namespace {

namespace h5 = mpm::h5;

const char* kFormat = "fragmpm grain file";

const char* kind_name(InputKind k) {
  switch (k) {
    case InputKind::grey:
      return "grey";
    case InputKind::classes:
      return "classes";
    case InputKind::labels:
      return "labels";
  }
  return "?";
}

template <class T, class Get>
void write_column(const h5::Group& g, const std::string& name, const std::vector<Grain>& grains,
                  const char* units, const char* description, Get get) {
  std::vector<T> values;
  values.reserve(grains.size());
  for (const Grain& grain : grains) values.push_back(static_cast<T>(get(grain)));
  const h5::Dataset ds = g.write<T>(name, values, {grains.size()});
  ds.set_attribute("units", units);
  ds.set_attribute("description", description);
}

template <class T>
std::vector<T> read_column(const h5::Group& g, const std::string& name, std::size_t n) {
  h5::Array<T> a = g.read<T>(name);
  if (a.dims != h5::Dims{n})
    throw mpm::RunFileError(
        g.describe(fmt::format("column '{}' has {} values, expected {} (one per grain)", name,
                               h5::element_count(a.dims), n)));
  return std::move(a.values);
}

std::vector<int> parse_ints(const h5::Object& o, const std::string& attribute, std::size_t count) {
  const std::string text = o.attribute_string(attribute);
  std::vector<int> v;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    try {
      v.push_back(std::stoi(item));
    } catch (const std::exception&) {
      break;
    }
  }
  if (v.size() != count)
    throw mpm::RunFileError(o.describe(fmt::format(
        "attribute '{}' = '{}' is not {} comma-separated integers", attribute, text, count)));
  return v;
}

}  // namespace

void write_grain_file(const std::string& path, const Segmentation& s,
                      const mpm::Particles<2>& particles, const GrainFileExtras& extras,
                      bool overwrite) {
  const h5::File file = h5::File::create(path, overwrite);
  const h5::Group root = file.root();
  root.set_attribute("format", kFormat);
  root.set_attribute("program_version", mpm::program_version());
  root.set_attribute("git_hash", mpm::program_git_hash());
  root.set_attribute("pixel_size", s.pixel_size);
  root.set_attribute("image_path", s.input.path);
  const cv::Rect& w = s.input.window;
  root.set_attribute("window", fmt::format("{},{},{},{}", w.x, w.y, w.width, w.height));
  root.set_attribute("image_size",
                     fmt::format("{},{}", s.input.full_size.width, s.input.full_size.height));
  root.set_attribute("input_kind", kind_name(s.kind));
  root.set_attribute("options", extras.options_text);
  root.set_attribute("units",
                     "SI (m, m2, kg/m3); 2D particle volumes and masses per unit thickness");

  const cv::Mat& labels = s.table.labels;
  std::vector<std::int32_t> flat(labels.total());
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c)
      flat[static_cast<std::size_t>(r) * labels.cols + c] = labels.at<std::int32_t>(r, c);
  const h5::Dataset ds = root.write<std::int32_t>(
      "labels", flat,
      {static_cast<std::size_t>(labels.rows), static_cast<std::size_t>(labels.cols)});
  ds.set_attribute("units", "1");
  ds.set_attribute("description",
                   "grain label per pixel (rows x cols, row 0 at the top), 0 = background");

  const h5::Group g = root.require_group("grains");
  const auto& gr = s.table.grains;
  using G = const Grain&;
  write_column<std::int32_t>(g, "label", gr, "1",
                             "grain label in /labels; body id of its particles = label - 1",
                             [](G x) { return x.label; });
  write_column<std::int64_t>(g, "pixels", gr, "1", "pixel count", [](G x) { return x.pixels; });
  write_column<double>(g, "area", gr, "m2", "area A", [](G x) { return x.shape.area; });
  write_column<double>(g, "equivalent_diameter", gr, "m", "sqrt(4A/pi)",
                       [](G x) { return x.shape.equivalent_diameter; });
  write_column<double>(g, "roundness", gr, "1", "4A/(pi a^2), a = major axis (ImageJ Round)",
                       [](G x) { return x.shape.roundness; });
  write_column<double>(g, "aspect_ratio", gr, "1", "major/minor axis (ImageJ AR)",
                       [](G x) { return x.shape.aspect_ratio; });
  write_column<double>(g, "centroid_x", gr, "m", "centroid, origin at the lower-left image corner",
                       [](G x) { return x.shape.centroid_x; });
  write_column<double>(g, "centroid_y", gr, "m", "centroid, y up",
                       [](G x) { return x.shape.centroid_y; });
  write_column<double>(g, "major_axis", gr, "m",
                       "major axis of the moment ellipse rescaled to area A",
                       [](G x) { return x.shape.major_axis; });
  write_column<double>(g, "minor_axis", gr, "m", "minor axis, pi a b / 4 = A",
                       [](G x) { return x.shape.minor_axis; });
  write_column<double>(g, "orientation", gr, "rad", "major-axis angle from +x towards +y",
                       [](G x) { return x.shape.orientation; });
  write_column<double>(g, "perimeter", gr, "m", "Cauchy-Crofton estimate (4 directions)",
                       [](G x) { return x.shape.perimeter; });
  write_column<double>(g, "centroid_col", gr, "px", "centroid column in the window",
                       [](G x) { return x.centroid_col; });
  write_column<double>(g, "centroid_row", gr, "px", "centroid row in the window (downwards)",
                       [](G x) { return x.centroid_row; });
  write_column<double>(g, "mean_grey", gr, "grey level", "mean grey level in the image's own units",
                       [](G x) { return x.mean_grey; });
  write_column<std::int32_t>(g, "phase", gr, "1", "material (phase) id from the grey-level bands",
                             [](G x) { return x.phase; });
  write_column<std::uint8_t>(g, "touches_border", gr, "1", "1 = cut by the window border",
                             [](G x) { return x.touches_border ? 1 : 0; });

  const h5::Group p = root.require_group("particles");
  mpm::write_particle_datasets<2>(p, particles, {});
  p.set_attribute("cell_size", extras.sampling.cell_size);
  p.set_attribute("particles_per_cell",
                  static_cast<std::int64_t>(extras.sampling.particles_per_cell));
  p.set_attribute("densities", fmt::format("{}", fmt::join(extras.density_of_material, ",")));
  file.flush();
}

GrainFile read_grain_file(const std::string& path) {
  const h5::File file = h5::File::open(path, false);
  const h5::Group root = file.root();
  if (!root.has_attribute("format") || root.attribute_string("format") != kFormat)
    throw mpm::RunFileError(root.describe("not a grain file (attribute 'format' is not '" +
                                          std::string(kFormat) + "')"));
  GrainFile out;
  out.path = path;
  out.image_path = root.attribute_string("image_path");
  out.pixel_size = root.attribute_double("pixel_size");
  const std::vector<int> w = parse_ints(root, "window", 4);
  out.window = cv::Rect(w[0], w[1], w[2], w[3]);

  const h5::Array<std::int32_t> labels = root.read<std::int32_t>("labels");
  if (labels.dims.size() != 2)
    throw mpm::RunFileError(root.describe("dataset 'labels' is not two-dimensional"));
  out.labels = cv::Mat(static_cast<int>(labels.dims[0]), static_cast<int>(labels.dims[1]), CV_32S);
  std::copy(labels.values.begin(), labels.values.end(), out.labels.ptr<std::int32_t>(0));

  const h5::Group g = root.open_group("grains");
  const std::size_t n = g.open_dataset("label").rows();
  const auto label = read_column<std::int32_t>(g, "label", n);
  const auto pixels = read_column<std::int64_t>(g, "pixels", n);
  const auto area = read_column<double>(g, "area", n);
  const auto eqd = read_column<double>(g, "equivalent_diameter", n);
  const auto round = read_column<double>(g, "roundness", n);
  const auto ar = read_column<double>(g, "aspect_ratio", n);
  const auto cx = read_column<double>(g, "centroid_x", n);
  const auto cy = read_column<double>(g, "centroid_y", n);
  const auto major = read_column<double>(g, "major_axis", n);
  const auto minor = read_column<double>(g, "minor_axis", n);
  const auto orient = read_column<double>(g, "orientation", n);
  const auto perim = read_column<double>(g, "perimeter", n);
  const auto ccol = read_column<double>(g, "centroid_col", n);
  const auto crow = read_column<double>(g, "centroid_row", n);
  const auto grey = read_column<double>(g, "mean_grey", n);
  const auto phase = read_column<std::int32_t>(g, "phase", n);
  const auto border = read_column<std::uint8_t>(g, "touches_border", n);
  out.grains.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    Grain& x = out.grains[k];
    x.label = label[k];
    x.pixels = pixels[k];
    x.shape.area = area[k];
    x.shape.equivalent_diameter = eqd[k];
    x.shape.roundness = round[k];
    x.shape.aspect_ratio = ar[k];
    x.shape.centroid_x = cx[k];
    x.shape.centroid_y = cy[k];
    x.shape.major_axis = major[k];
    x.shape.minor_axis = minor[k];
    x.shape.orientation = orient[k];
    x.shape.perimeter = perim[k];
    x.centroid_col = ccol[k];
    x.centroid_row = crow[k];
    x.mean_grey = grey[k];
    x.phase = phase[k];
    x.touches_border = border[k] != 0;
  }

  const h5::Group p = root.open_group("particles");
  out.particles = mpm::read_particle_datasets<2>(p);
  out.sampling.cell_size = p.attribute_double("cell_size");
  out.sampling.particles_per_cell = static_cast<int>(p.attribute_int64("particles_per_cell"));
  return out;
}

}  // namespace fragmpm::pipeline
