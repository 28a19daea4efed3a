#pragma once
// Grains → material points: particles on a regular lattice sample the label image;
// each takes the grain of the pixel it falls in, and particles next to another grain or to the
// background carry the surface flag that makes touching grains separable from the first step
// ([HH17] §2.4).
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/pipeline/segment_grains.hpp"

namespace fragmpm::pipeline {

struct ParticleSampling {
  double cell_size = 0.0;  ///< grid spacing h [m]
  int particles_per_cell =
      2;  ///< n per direction: particle spacing h/n, n² particles per cell (2D)
};

/// Material points of the grains of `labels` (CV_32SC1, 0 = background), in the physical frame of
/// the image (origin at its lower-left corner, x right, y up, SI). Lattice points ((i + ½) a,
/// (j + ½) a), a = h/n, inside the image; a point takes the label of the pixel it falls in and is
/// kept when that label is > 0. Per particle: body = label − 1 (the grain's row in /grains),
/// material = material_of_label[label], CPDI domain diag(a, a), volume0 = a² (per unit thickness),
/// mass = density_of_material[material] · a², F = I, everything else zero. surface = 1 when one of
/// the 8 lattice neighbours has another label or lies outside the image, so both sides of a contact
/// between grains are flagged.
/// Throws SegmentInputError for a non-positive cell size or particles per cell, a particle spacing
/// below a hundredth of a pixel, or a label without material / a material without density.
mpm::Particles<2> particles_from_labels(const cv::Mat& labels, double pixel_size,
                                        const ParticleSampling& sampling,
                                        const std::vector<std::int32_t>& material_of_label,
                                        const std::vector<double>& density_of_material);

/// material_of_label for a grain table: index = label, value = the grain's phase (entry 0 unused).
std::vector<std::int32_t> material_of_labels(const GrainTable& table);

/// A cell size that resolves the median grain by about `cells_per_grain` cells across its
/// equivalent diameter, rounded to a whole number of pixels (at least one) [m].
double auto_cell_size(const GrainTable& table, double pixel_size, double cells_per_grain = 8.0);

}  // namespace fragmpm::pipeline
