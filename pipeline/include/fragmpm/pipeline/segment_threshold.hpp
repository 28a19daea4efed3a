#pragma once
// Thresholding the working image into a grain mask and cleaning the mask up.
#include <opencv2/core/mat.hpp>
#include <string>

#include "fragmpm/pipeline/segment_image.hpp"
#include "fragmpm/pipeline/segment_options.hpp"

namespace fragmpm::pipeline {

/// A binary grain mask (CV_8UC1, 255 = grain) and the global level used (working-image units;
/// NaN for the adaptive threshold, which has none).
struct ThresholdResult {
  cv::Mat mask;
  double level = 0.0;
};

/// Grains are the pixels brighter than the threshold: Otsu's or the triangle method's level, a
/// fixed level (given in the image's own grey units), or brighter than the local mean minus
/// `adaptive_offset` over a `adaptive_block` window. Throws SegmentInputError (naming `name`) for
/// an image of one grey level, for invalid parameters (even or too small block, fixed level outside
/// the image's range is allowed but reported through the all-background/all-grain checks).
ThresholdResult threshold_grains(const WorkingImage& work, const ThresholdOptions& options,
                                 const std::string& name);

/// Opening (removes specks and thin bridges), closing (fills thin cracks) with disks of the given
/// radii, then filling of enclosed background regions (not connected to the image border) of at
/// most `max_hole_area` pixels.
cv::Mat clean_mask(const cv::Mat& mask, const CleanupOptions& options);

/// Throws SegmentInputError when the mask has no grain pixel or no background pixel; `what`
/// describes how the mask was made (for the message).
void check_mask_has_both(const cv::Mat& mask, const std::string& name, const std::string& what);

}  // namespace fragmpm::pipeline
