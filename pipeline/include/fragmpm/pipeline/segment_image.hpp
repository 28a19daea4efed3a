#pragma once
// Image loading and preprocessing for the segmentation: read PNG, TIFF (8- and
// 16-bit), BMP or JPEG, crop a window, convert colour to grey, and build the 8-bit working image
// (invert, stretch, denoise, equalise) that the thresholds run on.
#include <opencv2/core/mat.hpp>
#include <optional>
#include <string>

#include "fragmpm/pipeline/segment_options.hpp"

namespace fragmpm::pipeline {

/// An input image after loading and cropping.
struct LoadedImage {
  std::string path;
  cv::Mat image;       ///< the cropped window as read: 1, 3 or 4 channels, any depth
  cv::Mat grey;        ///< single channel in the image's own units and depth (see to_grey)
  cv::Rect window;     ///< the window in the input image's pixels (the whole image without crop)
  cv::Size full_size;  ///< size of the input image before cropping
};

/// Reads `path` (colour and bit depth kept), checks it and crops `crop`. Throws SegmentInputError
/// for a missing, unreadable or corrupt file, an image smaller than 2 × 2 pixels, or a crop window
/// that is empty or not inside the image.
LoadedImage load_image(const std::string& path, const std::optional<cv::Rect>& crop);

/// The same checks and crop for an image already in memory; `name` is used in messages.
LoadedImage prepare_image(const cv::Mat& image, const std::string& name,
                          const std::optional<cv::Rect>& crop);

/// Single-channel version of `image` in its own units: colour → luminance (ITU-R BT.601 weights,
/// OpenCV's BGR→grey), alpha dropped, depth kept.
cv::Mat to_grey(const cv::Mat& image);

/// The 8-bit working image and the linear map from the image's own grey units to it.
struct WorkingImage {
  cv::Mat image;      ///< CV_8UC1
  double lo = 0.0;    ///< image level mapped to 0 (before inversion)
  double hi = 255.0;  ///< image level mapped to 255 (before inversion)
  bool inverted = false;
  /// Gap detection replaced the grey levels (PreprocessOptions::gap_radius): fixed levels no longer
  /// refer to the image's own units.
  bool gaps = false;

  /// Working-image level of a grey level in the image's own units.
  double working_level(double image_level) const;
};

/// Builds the working image from `grey`: 8-bit images are used as they are, deeper ones (16-bit,
/// float) are stretched linearly from their minimum to their maximum onto 0–255 (as ImageJ does
/// for automatic thresholds); then optional inversion, denoising, gap detection and CLAHE
/// equalisation.
WorkingImage working_image(const cv::Mat& grey, const PreprocessOptions& options);

}  // namespace fragmpm::pipeline
