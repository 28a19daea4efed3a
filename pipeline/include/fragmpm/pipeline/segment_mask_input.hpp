#pragma once
// Already-segmented input: class masks with a boundary class (as the Miocene
// sandstone and Torrey Pines masks: 0 background, 1 grain, 2 boundary line) and label images.
#include <opencv2/core/mat.hpp>
#include <string>

#include "fragmpm/pipeline/segment_options.hpp"

namespace fragmpm::pipeline {

/// Grains of a class mask: 4-connected patches of the grain classes, separated by the boundary
/// classes; with `boundary_to_grains` the boundary pixels then join the nearest grain
/// (breadth-first through boundary pixels), so grains that touch in the sample touch in the labels.
/// `classes` is a single-channel integer image (values compared exactly). Throws SegmentInputError
/// (naming `name`) when no pixel has a grain class or every pixel does.
cv::Mat labels_from_classes(const cv::Mat& classes, const ClassMaskOptions& options,
                            const std::string& name);

/// Grains of a label image: every 4-connected patch of one non-zero value is a grain (a label used
/// for two separate patches gives two grains). Returns compact CV_32SC1 labels. Throws
/// SegmentInputError when every pixel is zero or the whole image is one value.
cv::Mat labels_from_label_image(const cv::Mat& image, const std::string& name);

}  // namespace fragmpm::pipeline
