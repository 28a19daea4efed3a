#pragma once
// Raster view of fragments (docs/design.md): particle domains (CPDI parallelograms x ± r1/2 ± r2/2)
// drawn into a mask with OpenCV, connected components of that mask, and the comparison with the
// graph labelling of fragments.hpp. The picture joins fragments whose domains touch or overlap
// (pieces pressed together), which the graph keeps apart; on well-separated fragments the two must
// agree.
//
// Raster frame: pixel (col, row) covers x ∈ [x0 + col·s, x0 + (col+1)·s), y ∈ [y0 + row·s, …), i.e.
// rows grow with y (the image is stored upside down relative to a picture; labelling does not
// care).
#include <cstddef>
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <span>
#include <string>
#include <vector>

#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

/// A CV_8UC1 mask (255 inside) of some particles' domains over a window.
struct ParticleRaster {
  cv::Mat mask;
  double pixel_size = 0.0;  ///< s [m]
  double x0 = 0.0;          ///< lower-left corner of pixel (0, 0) [m]
  double y0 = 0.0;
};

/// Draws the domains of `subset` (particle indices) with cv::fillConvexPoly (sub-pixel vertices) at
/// pixel size `pixel_size`, over their bounding box grown by `pad_pixels` on every side. Throws
/// std::invalid_argument for a non-positive pixel size, an empty subset, or a raster that would
/// exceed 2·10⁸ pixels.
ParticleRaster draw_particle_domains(const mpm::Particles<2>& particles,
                                     std::span<const std::size_t> subset, double pixel_size,
                                     int pad_pixels = 2);

/// The pixel holding point (x, y) of the raster, or (−1, −1) when outside.
cv::Point raster_pixel(const ParticleRaster& raster, double x, double y);

/// Connected components of the domains of all unmasked particles.
struct RasterLabels {
  ParticleRaster raster;
  cv::Mat components;                   ///< CV_32S, 0 = background, 1 … count
  int count = 0;                        ///< number of connected components (background excluded)
  std::vector<std::int32_t> component;  ///< per particle: component at its centre, −1 when masked
};

/// Pixel size used when none is given: a quarter of the median local spacing of the unmasked
/// particles, so a masked row one particle wide is 4 pixels wide and stays a gap.
double default_raster_pixel_size(const mpm::Particles<2>& particles, const FragmentLabels& labels);

/// Draws every unmasked particle (labels.fragment ≥ 0) and labels the mask with
/// cv::connectedComponents, 4-connectivity (pixels touching only at a corner are not joined).
/// `pixel_size` ≤ 0 means default_raster_pixel_size.
RasterLabels raster_fragments(const mpm::Particles<2>& particles, const FragmentLabels& labels,
                              double pixel_size = 0.0);

/// How the graph fragments and the raster components correspond, through the component at each
/// unmasked particle's centre.
struct LabellingComparison {
  std::size_t graph_fragments = 0;    ///< fragments of the graph labelling (fines included)
  std::size_t raster_components = 0;  ///< components of the raster
  std::size_t split = 0;   ///< graph fragments whose particles lie in more than one component
  std::size_t merged = 0;  ///< components holding particles of more than one graph fragment
  std::size_t empty = 0;   ///< components with no particle centre in them (slivers)
  /// One-to-one: every fragment is exactly one component and every component exactly one fragment.
  bool agree() const {
    return split == 0 && merged == 0 && empty == 0 && graph_fragments == raster_components;
  }
  std::string summary() const;  ///< one line for logs
};

LabellingComparison compare_labellings(const FragmentLabels& graph, const RasterLabels& raster);

}  // namespace fragmpm::analysis
