#pragma once
// The segmentation preview: the micrograph with every grain's outline in its own
// colour and its label number at its centroid; grains that were dropped (too small, cut by the
// border) are tinted red; a strip below states the grain count, median size and pixel size.
#include <opencv2/core/mat.hpp>
#include <string>

#include "fragmpm/pipeline/segment.hpp"

namespace fragmpm::pipeline {

/// The preview as an 8-bit BGR image (image width × (height + caption strip)).
cv::Mat draw_preview(const Segmentation& segmentation);

/// Writes `preview` as PNG (or any format OpenCV infers from the extension). Throws
/// SegmentInputError when the file cannot be written.
void write_preview(const cv::Mat& preview, const std::string& path);

}  // namespace fragmpm::pipeline
