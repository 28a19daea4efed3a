#pragma once
// Writing figures as PNG (OpenCV imgcodecs).
#include <opencv2/core/mat.hpp>
#include <string>

namespace fragmpm::analysis {

/// Writes an 8-bit BGR image as PNG. Throws FigureError when `path` does not end in .png or the
/// file cannot be written (missing directory, no permission). Replaces an existing file: callers
/// that must not overwrite check first.
void write_png(const cv::Mat& image, const std::string& path);

}  // namespace fragmpm::analysis
