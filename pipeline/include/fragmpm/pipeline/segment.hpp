#pragma once
// Micrograph → grains: the whole segmentation of one image, from file or from memory.
//   grey input:    working image → threshold → clean-up → watershed split → hole filling
//   class mask:    grain patches separated by the boundary class, boundary given to the grains
//   label image:   4-connected patches of one value
// then grains under the minimum area (and, optionally, those cut by the border) are dropped and
// the rest measured (segment_grains.hpp).
#include <opencv2/core/mat.hpp>
#include <string>

#include "fragmpm/pipeline/segment_grains.hpp"
#include "fragmpm/pipeline/segment_image.hpp"
#include "fragmpm/pipeline/segment_options.hpp"

namespace fragmpm::pipeline {

struct Segmentation {
  LoadedImage input;        ///< the cropped image, its grey version and the window
  double pixel_size = 0.0;  ///< [m]
  InputKind kind = InputKind::grey;
  /// Global threshold in the image's own grey units (NaN for adaptive thresholds and mask input).
  double threshold_level = 0.0;
  GrainTable table;
};

/// Throws SegmentInputError for impossible options (non-positive pixel size, unordered phase
/// bands, negative radii, neck ratio outside [0, 1], …), naming the option.
void validate_segment_options(const SegmentOptions& options);

/// Segments the image file options.image_path.
Segmentation segment(const SegmentOptions& options);

/// Segments an image already in memory; options.image_path only names it in messages.
Segmentation segment(const cv::Mat& image, const SegmentOptions& options);

/// Segments an image that has been loaded and cropped.
Segmentation segment(LoadedImage input, const SegmentOptions& options);

}  // namespace fragmpm::pipeline
