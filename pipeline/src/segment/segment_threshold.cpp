#include "fragmpm/pipeline/segment_threshold.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <opencv2/imgproc.hpp>

namespace fragmpm::pipeline {

namespace {

cv::Mat disk(int radius) {
  return cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1));
}

}  // namespace

ThresholdResult threshold_grains(const WorkingImage& work, const ThresholdOptions& options,
                                 const std::string& name) {
  double lo = 0.0, hi = 0.0;
  cv::minMaxLoc(work.image, &lo, &hi);
  if (lo == hi)
    throw SegmentInputError(
        fmt::format("{}: every pixel has the same grey level; there is nothing to segment", name));
  ThresholdResult out;
  switch (options.method) {
    case ThresholdMethod::otsu:
      out.level = cv::threshold(work.image, out.mask, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
      break;
    case ThresholdMethod::triangle:
      out.level =
          cv::threshold(work.image, out.mask, 0, 255, cv::THRESH_BINARY | cv::THRESH_TRIANGLE);
      break;
    case ThresholdMethod::fixed: {
      out.level = work.working_level(options.level);
      cv::threshold(work.image, out.mask, out.level, 255, cv::THRESH_BINARY);
      break;
    }
    case ThresholdMethod::adaptive: {
      const int block = options.adaptive_block;
      if (block < 3 || block % 2 == 0)
        throw SegmentInputError(
            fmt::format("{}: adaptive threshold block must be an odd number of pixels ≥ 3, got {}",
                        name, block));
      // dst = src > local mean − C with C = offset.
      cv::adaptiveThreshold(work.image, out.mask, 255, cv::ADAPTIVE_THRESH_MEAN_C,
                            cv::THRESH_BINARY, block, options.adaptive_offset);
      out.level = std::numeric_limits<double>::quiet_NaN();
      break;
    }
  }
  return out;
}

cv::Mat clean_mask(const cv::Mat& mask, const CleanupOptions& options) {
  cv::Mat out = mask.clone();
  if (options.open_radius > 0)
    cv::morphologyEx(out, out, cv::MORPH_OPEN, disk(options.open_radius));
  if (options.close_radius > 0)
    cv::morphologyEx(out, out, cv::MORPH_CLOSE, disk(options.close_radius));
  if (options.max_hole_area > 0) {
    // Background components that do not reach the image border are enclosed by grain.
    cv::Mat background = out == 0;
    cv::Mat comp, stats, centroids;
    const int n = cv::connectedComponentsWithStats(background, comp, stats, centroids, 4, CV_32S);
    std::vector<unsigned char> fill(static_cast<std::size_t>(n), 0);
    for (int k = 1; k < n; ++k) {
      const int x = stats.at<int>(k, cv::CC_STAT_LEFT), y = stats.at<int>(k, cv::CC_STAT_TOP);
      const int w = stats.at<int>(k, cv::CC_STAT_WIDTH), h = stats.at<int>(k, cv::CC_STAT_HEIGHT);
      const bool inside = x > 0 && y > 0 && x + w < out.cols && y + h < out.rows;
      fill[static_cast<std::size_t>(k)] =
          inside && stats.at<int>(k, cv::CC_STAT_AREA) <= options.max_hole_area;
    }
    for (int r = 0; r < out.rows; ++r) {
      const int* cr = comp.ptr<int>(r);
      unsigned char* m = out.ptr<unsigned char>(r);
      for (int c = 0; c < out.cols; ++c)
        if (fill[static_cast<std::size_t>(cr[c])]) m[c] = 255;
    }
  }
  return out;
}

void check_mask_has_both(const cv::Mat& mask, const std::string& name, const std::string& what) {
  const int grain = cv::countNonZero(mask);
  if (grain == 0)
    throw SegmentInputError(fmt::format(
        "{}: no grain pixels ({}); grains must be brighter than the background — pass --invert "
        "for dark grains, or choose another threshold",
        name, what));
  if (grain == static_cast<int>(mask.total()))
    throw SegmentInputError(fmt::format(
        "{}: every pixel is grain ({}); there is no background to tell grains apart — pass "
        "--invert for dark grains, or choose another threshold",
        name, what));
}

}  // namespace fragmpm::pipeline
