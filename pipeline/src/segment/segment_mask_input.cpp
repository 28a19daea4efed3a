#include "fragmpm/pipeline/segment_mask_input.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <set>
#include <vector>

#include "fragmpm/pipeline/segment_threshold.hpp"
#include "fragmpm/pipeline/segment_watershed.hpp"

namespace fragmpm::pipeline {

namespace {

cv::Mat as_int32(const cv::Mat& image) {
  cv::Mat out;
  image.convertTo(out, CV_32S);  // rounds floating values
  return out;
}

cv::Mat membership(const cv::Mat& values, const std::vector<int>& classes) {
  cv::Mat out = cv::Mat::zeros(values.size(), CV_8U);
  for (const int v : classes) out |= (values == v);
  return out;
}

std::string value_list(const cv::Mat& values) {
  std::set<std::int32_t> seen;
  for (int r = 0; r < values.rows && seen.size() <= 10; ++r)
    for (int c = 0; c < values.cols && seen.size() <= 10; ++c)
      seen.insert(values.at<std::int32_t>(r, c));
  std::vector<std::int32_t> v(seen.begin(), seen.end());
  if (v.size() > 10) {
    v.resize(10);
    return fmt::format("{}, …", fmt::join(v, ", "));
  }
  return fmt::format("{}", fmt::join(v, ", "));
}

}  // namespace

cv::Mat labels_from_classes(const cv::Mat& classes, const ClassMaskOptions& options,
                            const std::string& name) {
  if (options.grain_classes.empty())
    throw SegmentInputError(fmt::format("{}: no grain class given for the class mask", name));
  for (const int g : options.grain_classes)
    if (std::find(options.boundary_classes.begin(), options.boundary_classes.end(), g) !=
        options.boundary_classes.end())
      throw SegmentInputError(fmt::format(
          "{}: class {} is given both as a grain class and as a boundary class", name, g));
  const cv::Mat values = as_int32(classes);
  const cv::Mat grain = membership(values, options.grain_classes);
  if (cv::countNonZero(grain) == 0)
    throw SegmentInputError(fmt::format(
        "{}: no pixel has a grain class ({}); the mask holds the values {} — is this a class mask?",
        name, fmt::join(options.grain_classes, ", "), value_list(values)));
  check_mask_has_both(grain, name,
                      fmt::format("grain classes {}", fmt::join(options.grain_classes, ", ")));
  cv::Mat labels = connected_labels(grain);
  if (options.boundary_to_grains && !options.boundary_classes.empty()) {
    const cv::Mat boundary = membership(values, options.boundary_classes);
    labels = flood_labels(labels, grain | boundary);
  }
  return labels;
}

cv::Mat labels_from_label_image(const cv::Mat& image, const std::string& name) {
  const cv::Mat values = as_int32(image);
  const int rows = values.rows, cols = values.cols;
  if (cv::countNonZero(values) == 0)
    throw SegmentInputError(
        fmt::format("{}: every pixel is 0; a label image needs non-zero grain labels", name));
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(values, &lo, &hi);
  if (lo == hi)
    throw SegmentInputError(fmt::format(
        "{}: every pixel has the label {}; there is no background to tell grains apart", name, lo));
  cv::Mat labels = cv::Mat::zeros(values.size(), CV_32S);
  std::int32_t next = 0;
  std::vector<int> stack;
  for (int r0 = 0; r0 < rows; ++r0) {
    for (int c0 = 0; c0 < cols; ++c0) {
      const std::int32_t v = values.at<std::int32_t>(r0, c0);
      if (v == 0 || labels.at<std::int32_t>(r0, c0) != 0) continue;
      ++next;
      labels.at<std::int32_t>(r0, c0) = next;
      stack.assign(1, r0 * cols + c0);
      while (!stack.empty()) {  // 4-connected flood fill over pixels of the same value
        const int i = stack.back();
        stack.pop_back();
        const int r = i / cols, c = i % cols;
        const int nr[4] = {r - 1, r + 1, r, r}, nc[4] = {c, c, c - 1, c + 1};
        for (int k = 0; k < 4; ++k) {
          if (nr[k] < 0 || nc[k] < 0 || nr[k] >= rows || nc[k] >= cols) continue;
          if (values.at<std::int32_t>(nr[k], nc[k]) != v ||
              labels.at<std::int32_t>(nr[k], nc[k]) != 0)
            continue;
          labels.at<std::int32_t>(nr[k], nc[k]) = next;
          stack.push_back(nr[k] * cols + nc[k]);
        }
      }
    }
  }
  return labels;
}

}  // namespace fragmpm::pipeline
