#include "fragmpm/pipeline/segment_bodies.hpp"

#include <fmt/format.h>

#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_file.hpp"

namespace fragmpm::pipeline {

namespace {

GrainBodies make_bodies(const cv::Mat& labels, std::vector<Grain> grains, double pixel_size,
                        const ParticleSampling& sampling,
                        const std::vector<double>& density_of_phase, const std::string& source) {
  std::vector<std::int32_t> material(grains.size() + 1, 0);
  for (const Grain& g : grains) {
    if (g.phase < 0 || static_cast<std::size_t>(g.phase) >= density_of_phase.size())
      throw SegmentInputError(
          fmt::format("{}: grain {} is phase {} but densities are given for {} phase(s)", source,
                      g.label, g.phase, density_of_phase.size()));
    material[static_cast<std::size_t>(g.label)] = g.phase;
  }
  GrainBodies b;
  b.particles = particles_from_labels(labels, pixel_size, sampling, material, density_of_phase);
  b.pixel_size = pixel_size;
  b.width = labels.cols * pixel_size;
  b.height = labels.rows * pixel_size;
  for (const Grain& g : grains) b.body_names.push_back(fmt::format("grain {}", g.label));
  b.grains = std::move(grains);
  return b;
}

}  // namespace

GrainBodies grain_bodies_from_image(const SegmentOptions& options, const ParticleSampling& sampling,
                                    const std::vector<double>& density_of_phase) {
  Segmentation s = segment(options);
  return make_bodies(s.table.labels, std::move(s.table.grains), s.pixel_size, sampling,
                     density_of_phase, s.input.path);
}

GrainBodies grain_bodies_from_file(const std::string& path, const ParticleSampling& sampling,
                                   const std::vector<double>& density_of_phase) {
  GrainFile f = read_grain_file(path);
  return make_bodies(f.labels, std::move(f.grains), f.pixel_size, sampling, density_of_phase, path);
}

}  // namespace fragmpm::pipeline
