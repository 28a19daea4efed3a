#pragma once
// A column of real grains for crushing scenes ([XLS21] §4.5): chosen grains of a segmented image
// stacked one on top of the other, touching, centred on one vertical axis, and a new pixel size
// that gives the column a prescribed total grain area. The result is a label image that `fragmpm
// segment --input labels` (or `segment(image, options)`) turns into a grain file.
#include <opencv2/core/mat.hpp>
#include <vector>

namespace fragmpm::pipeline {

struct GrainColumn {
  /// CV_16UC1 label image, row 0 at the top: the k-th chosen grain (bottom first) has value k + 1,
  /// background 0. `margin` pixels of background surround the column.
  cv::Mat labels;
  double pixel_size = 0.0;     ///< [m] so that the grains' pixel area is the requested total area
  long long grain_pixels = 0;  ///< pixels of all grains together
};

/// Stacks the grains `chosen` (labels of `labels`, CV_32SC1, bottom grain first) into a column.
/// Each grain keeps its shape and orientation; its centroid column is put on the column's axis and
/// it is lowered onto the grain below until one more row down would overlap it, so neighbours touch
/// (share an edge or a corner of pixels) without overlapping. `total_area` [m²] fixes the pixel
/// size: pixel_size = √(total_area / grain_pixels). Throws std::invalid_argument for an empty
/// choice, a label not in the image, a repeated label, a non-positive area or a negative margin.
GrainColumn stack_grains(const cv::Mat& labels, const std::vector<int>& chosen, double total_area,
                         int margin);

}  // namespace fragmpm::pipeline
