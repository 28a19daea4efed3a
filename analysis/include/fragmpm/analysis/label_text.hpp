#pragma once
// Text on images made outside the figure code (the segmentation preview): the figures' font,
// UTF-8 (µ, °, ²) drawn as itself.
#include <opencv2/core.hpp>
#include <string>

#include "fragmpm/analysis/colour_map.hpp"

namespace fragmpm::analysis {

/// Size in pixels of `utf8` at `scale` (1 ≈ 22 px capitals, as the figures' text).
cv::Size label_extent(const std::string& utf8, double scale);

/// Draws `utf8` on a BGR image with the top left of its box at `top_left`.
void draw_label(cv::Mat& image, const std::string& utf8, cv::Point top_left, double scale,
                Rgb colour);

}  // namespace fragmpm::analysis
