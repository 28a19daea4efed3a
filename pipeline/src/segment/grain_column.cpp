// Real grain outlines stacked into a column and scaled to a total area (grain_column.hpp).
#include "fragmpm/pipeline/grain_column.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>
#include <string>

namespace fragmpm::pipeline {

namespace {

/// One chosen grain cut out of the label image: its mask (CV_8U, 255 = grain) in its bounding box
/// and the column of its centroid within that box.
struct GrainPatch {
  cv::Mat mask;
  double centroid_col = 0.0;
};

GrainPatch cut_out(const cv::Mat& labels, int label) {
  const cv::Mat whole = labels == label;
  const cv::Rect box = cv::boundingRect(whole);
  if (box.area() == 0)
    throw std::invalid_argument("stack_grains: label " + std::to_string(label) +
                                " is not in the label image");
  GrainPatch p;
  p.mask = whole(box).clone();
  const cv::Moments m = cv::moments(p.mask, true);
  p.centroid_col = m.m10 / m.m00;
  return p;
}

}  // namespace

GrainColumn stack_grains(const cv::Mat& labels, const std::vector<int>& chosen, double total_area,
                         int margin) {
  if (labels.type() != CV_32SC1)
    throw std::invalid_argument("stack_grains: expected a CV_32SC1 label image");
  if (chosen.empty()) throw std::invalid_argument("stack_grains: no grains chosen");
  if (std::set<int>(chosen.begin(), chosen.end()).size() != chosen.size())
    throw std::invalid_argument("stack_grains: a grain is chosen twice");
  if (!(total_area > 0.0))
    throw std::invalid_argument("stack_grains: the total area must be positive");
  if (margin < 0) throw std::invalid_argument("stack_grains: the margin must be >= 0");
  if (chosen.size() > std::numeric_limits<std::uint16_t>::max())
    throw std::invalid_argument("stack_grains: too many grains for a 16-bit label image");

  std::vector<GrainPatch> patches;
  for (int label : chosen) patches.push_back(cut_out(labels, label));

  // Horizontal placement: every centroid on one axis; `left` is the axis's distance from the
  // column's left edge in pixels.
  std::vector<int> shift(patches.size());  // column of each patch's left edge, axis at 0
  int left = 0, right = 0;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    shift[k] = -static_cast<int>(std::lround(patches[k].centroid_col));
    left = std::max(left, -shift[k]);
    right = std::max(right, shift[k] + patches[k].mask.cols);
  }
  const int width = left + right;

  // Vertical placement, y counted up from the column's bottom row: `top[c]` is the highest row
  // taken in column c so far (−1 when empty). A grain's lowest pixel in column c must sit above
  // top[c]; the smallest such lift makes it touch the grains below.
  std::vector<int> top(static_cast<std::size_t>(width), -1);
  std::vector<int> lift(patches.size());
  int height = 0;
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const cv::Mat& m = patches[k].mask;
    int needed = 0;
    for (int c = 0; c < m.cols; ++c) {
      const int column = left + shift[k] + c;
      for (int r = m.rows - 1; r >= 0; --r)  // the lowest pixel is the largest row
        if (m.at<std::uint8_t>(r, c)) {
          const int lowest = m.rows - 1 - r;  // its y within the patch
          needed = std::max(needed, top[static_cast<std::size_t>(column)] + 1 - lowest);
          break;
        }
    }
    lift[k] = needed;
    for (int c = 0; c < m.cols; ++c) {
      const int column = left + shift[k] + c;
      for (int r = 0; r < m.rows; ++r)  // the highest pixel is the smallest row
        if (m.at<std::uint8_t>(r, c)) {
          top[static_cast<std::size_t>(column)] =
              std::max(top[static_cast<std::size_t>(column)], needed + m.rows - 1 - r);
          break;
        }
    }
    height = std::max(height, needed + m.rows);
  }

  GrainColumn out;
  out.labels = cv::Mat::zeros(height + 2 * margin, width + 2 * margin, CV_16UC1);
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const cv::Mat& m = patches[k].mask;
    for (int r = 0; r < m.rows; ++r)
      for (int c = 0; c < m.cols; ++c) {
        if (!m.at<std::uint8_t>(r, c)) continue;
        const int y = lift[k] + m.rows - 1 - r;
        const int row = margin + height - 1 - y;
        const int column = margin + left + shift[k] + c;
        out.labels.at<std::uint16_t>(row, column) = static_cast<std::uint16_t>(k + 1);
        ++out.grain_pixels;
      }
  }
  out.pixel_size = std::sqrt(total_area / static_cast<double>(out.grain_pixels));
  return out;
}

}  // namespace fragmpm::pipeline
