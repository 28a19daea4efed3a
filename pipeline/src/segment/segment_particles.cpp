#include "fragmpm/pipeline/segment_particles.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "fragmpm/pipeline/segment_options.hpp"

namespace fragmpm::pipeline {

mpm::Particles<2> particles_from_labels(const cv::Mat& labels, double pixel_size,
                                        const ParticleSampling& sampling,
                                        const std::vector<std::int32_t>& material_of_label,
                                        const std::vector<double>& density_of_material) {
  if (labels.type() != CV_32SC1)
    throw SegmentInputError("particles_from_labels: the label image must be CV_32SC1");
  if (!(pixel_size > 0.0))
    throw SegmentInputError(fmt::format("pixel size must be positive, got {} m", pixel_size));
  if (!(sampling.cell_size > 0.0) || !std::isfinite(sampling.cell_size))
    throw SegmentInputError(
        fmt::format("cell size must be positive, got {} m", sampling.cell_size));
  if (sampling.particles_per_cell < 1)
    throw SegmentInputError(
        fmt::format("particles per cell must be ≥ 1, got {}", sampling.particles_per_cell));
  const double a = sampling.cell_size / sampling.particles_per_cell;
  if (a < 0.01 * pixel_size)
    throw SegmentInputError(fmt::format(
        "particle spacing {} m (cell size / particles per cell) is below a hundredth of the pixel "
        "size {} m",
        a, pixel_size));

  const int rows = labels.rows, cols = labels.cols;
  const double width = cols * pixel_size, height = rows * pixel_size;
  // Lattice points (i + ½) a strictly inside the image.
  const int nx = std::max(0, static_cast<int>(std::ceil(width / a - 0.5)));
  const int ny = std::max(0, static_cast<int>(std::ceil(height / a - 0.5)));
  std::vector<std::int32_t> lattice(static_cast<std::size_t>(nx) * ny, 0);
  for (int j = 0; j < ny; ++j) {
    const double y = (j + 0.5) * a;
    const int row =
        std::clamp(rows - 1 - static_cast<int>(std::floor(y / pixel_size)), 0, rows - 1);
    const auto* lrow = labels.ptr<std::int32_t>(row);
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) * a;
      const int col = std::clamp(static_cast<int>(std::floor(x / pixel_size)), 0, cols - 1);
      lattice[static_cast<std::size_t>(j) * nx + i] = std::max(0, lrow[col]);
    }
  }
  auto label_at = [&](int i, int j) -> std::int32_t {
    if (i < 0 || j < 0 || i >= nx || j >= ny) return 0;
    return lattice[static_cast<std::size_t>(j) * nx + i];
  };
  std::size_t count = 0;
  for (const std::int32_t l : lattice) count += l > 0;

  mpm::Particles<2> p;
  p.resize(count);
  std::size_t k = 0;
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const std::int32_t l = label_at(i, j);
      if (l <= 0) continue;
      if (static_cast<std::size_t>(l) >= material_of_label.size())
        throw SegmentInputError(
            fmt::format("grain label {} has no material (material list covers labels < {})", l,
                        material_of_label.size()));
      const std::int32_t m = material_of_label[static_cast<std::size_t>(l)];
      if (m < 0 || static_cast<std::size_t>(m) >= density_of_material.size())
        throw SegmentInputError(
            fmt::format("grain {} has material {} but densities are given for {} material(s)", l, m,
                        density_of_material.size()));
      bool surface = false;
      for (int dj = -1; dj <= 1 && !surface; ++dj)
        for (int di = -1; di <= 1 && !surface; ++di)
          if ((di || dj) && label_at(i + di, j + dj) != l) surface = true;
      p.x[k] = mpm::Vec<2>((i + 0.5) * a, (j + 0.5) * a);
      p.domain[k] = mpm::Mat<2>::Identity() * a;
      p.volume0[k] = a * a;
      p.mass[k] = density_of_material[static_cast<std::size_t>(m)] * a * a;
      p.surface[k] = surface ? 1 : 0;
      p.body[k] = l - 1;
      p.material[k] = m;
      ++k;
    }
  }
  return p;
}

std::vector<std::int32_t> material_of_labels(const GrainTable& table) {
  std::vector<std::int32_t> out(table.grains.size() + 1, 0);
  for (const Grain& g : table.grains) out[static_cast<std::size_t>(g.label)] = g.phase;
  return out;
}

double auto_cell_size(const GrainTable& table, double pixel_size, double cells_per_grain) {
  std::vector<double> d;
  d.reserve(table.grains.size());
  for (const Grain& g : table.grains) d.push_back(g.shape.equivalent_diameter);
  if (d.empty()) return pixel_size;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  const double median = d[d.size() / 2];
  const double pixels = std::max(1.0, std::round(median / cells_per_grain / pixel_size));
  return pixels * pixel_size;
}

}  // namespace fragmpm::pipeline
