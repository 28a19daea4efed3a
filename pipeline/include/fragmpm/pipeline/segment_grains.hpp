#pragma once
// The grain table (docs/design.md /grains): grains filtered by size and border, numbered
// 1..N, with the shape measures of analysis/region_shape (ImageJ definitions, shared with the
// fragment statistics) and a phase from grey-level bands.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <vector>

#include "fragmpm/analysis/region_shape.hpp"

namespace fragmpm::pipeline {

struct Grain {
  std::int32_t label = 0;  ///< 1..N; row label − 1 of the table
  std::int64_t pixels = 0;
  /// Area [m²], equivalent diameter [m], centroid [m], axes [m], orientation [rad], roundness,
  /// aspect ratio, perimeter [m]; physical frame: origin at the lower-left image corner, y up.
  analysis::RegionShape shape;
  double centroid_col = 0.0;  ///< [px] in the (cropped) image, pixel centres at integer + ½
  double centroid_row = 0.0;  ///< [px], rows counted downwards
  cv::Rect bbox;              ///< [px]
  double mean_grey = 0.0;     ///< mean grey level in the image's own units
  std::int32_t phase = 0;     ///< material (phase) id from the grey-level bands
  bool touches_border = false;
};

struct GrainTable {
  cv::Mat labels;                   ///< CV_32SC1, 0 = background, grain k has label k (1..N)
  std::vector<Grain> grains;        ///< grains[k − 1].label == k
  cv::Mat dropped;                  ///< CV_8UC1, 255 where a dropped grain was
  std::int64_t dropped_small = 0;   ///< grains under the minimum area
  std::int64_t dropped_border = 0;  ///< grains cut by the image border (when dropping them)
};

/// Phase of a grain with mean grey level `mean_grey` given ascending band limits: 0 below
/// bands[0], k between bands[k−1] and bands[k], bands.size() above the last.
std::int32_t phase_of(double mean_grey, const std::vector<double>& bands);

/// Measures the grains of `raw_labels` (CV_32SC1, 0 = background, any numbering), drops those with
/// fewer than `min_area` pixels and, with `drop_border`, those touching the image border, and
/// renumbers the rest 1..N in order of their old labels. `grey` (single channel, same size) gives
/// the mean grey level and, through `phase_bands`, the phase of each grain. `pixel_size` in m.
GrainTable measure_grains(const cv::Mat& raw_labels, const cv::Mat& grey, double pixel_size,
                          std::int64_t min_area, bool drop_border,
                          const std::vector<double>& phase_bands);

}  // namespace fragmpm::pipeline
