#include "fragmpm/pipeline/segment_preview.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "fragmpm/analysis/label_text.hpp"

namespace fragmpm::pipeline {

namespace {

/// The image as 8-bit BGR for display: 16-bit, float and mask images are stretched min → max so
/// that class and label values (0, 1, 2, …) become visible.
cv::Mat display_background(const Segmentation& s) {
  const cv::Mat& image = s.input.image;
  cv::Mat eight;
  const bool stretch = image.depth() != CV_8U || s.kind != InputKind::grey;
  if (stretch) {
    const cv::Mat grey = image.channels() == 1 ? image : s.input.grey;
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(grey, &lo, &hi);
    if (hi <= lo) hi = lo + 1.0;
    grey.convertTo(eight, CV_8U, 255.0 / (hi - lo), -lo * 255.0 / (hi - lo));
  } else {
    eight = image;
  }
  cv::Mat bgr;
  switch (eight.channels()) {
    case 1:
      cv::cvtColor(eight, bgr, cv::COLOR_GRAY2BGR);
      break;
    case 4:
      cv::cvtColor(eight, bgr, cv::COLOR_BGRA2BGR);
      break;
    case 3:
      bgr = eight.clone();
      break;
    default: {
      cv::Mat first;
      cv::extractChannel(eight, first, 0);
      cv::cvtColor(first, bgr, cv::COLOR_GRAY2BGR);
    }
  }
  return bgr;
}

// Bright, mutually distinct outline colours (BGR); red is kept for dropped grains.
const std::array<cv::Vec3b, 8> kPalette{
    cv::Vec3b(0, 255, 255),    // yellow
    cv::Vec3b(255, 255, 0),    // cyan
    cv::Vec3b(0, 255, 0),      // green
    cv::Vec3b(255, 0, 255),    // magenta
    cv::Vec3b(0, 165, 255),    // orange
    cv::Vec3b(255, 128, 0),    // azure
    cv::Vec3b(128, 255, 128),  // light green
    cv::Vec3b(255, 128, 255),  // pink
};

}  // namespace

cv::Mat draw_preview(const Segmentation& s) {
  cv::Mat canvas = display_background(s);
  const cv::Mat& labels = s.table.labels;
  const int rows = labels.rows, cols = labels.cols;

  // Dropped grains: tinted red, so the user sees what the filters removed.
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (s.table.dropped.at<unsigned char>(r, c)) {
        cv::Vec3b& px = canvas.at<cv::Vec3b>(r, c);
        px = cv::Vec3b(static_cast<unsigned char>(px[0] / 2), static_cast<unsigned char>(px[1] / 2),
                       static_cast<unsigned char>(128 + px[2] / 2));
      }

  // Outlines: grain pixels with a 4-neighbour of another label; thicker on large images.
  const int thickness = std::max(1, std::min(rows, cols) / 700);
  cv::Mat outline_label = cv::Mat::zeros(labels.size(), CV_32S);
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const std::int32_t l = labels.at<std::int32_t>(r, c);
      if (l <= 0) continue;
      const bool edge = (r > 0 && labels.at<std::int32_t>(r - 1, c) != l) ||
                        (r + 1 < rows && labels.at<std::int32_t>(r + 1, c) != l) ||
                        (c > 0 && labels.at<std::int32_t>(r, c - 1) != l) ||
                        (c + 1 < cols && labels.at<std::int32_t>(r, c + 1) != l);
      if (edge) outline_label.at<std::int32_t>(r, c) = l;
    }
  }
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const std::int32_t l = outline_label.at<std::int32_t>(r, c);
      if (l <= 0) continue;
      const cv::Vec3b colour = kPalette[static_cast<std::size_t>(l) % kPalette.size()];
      // Thicken inwards only, so neighbouring grains keep their own colours.
      for (int dr = -(thickness - 1); dr <= thickness - 1; ++dr)
        for (int dc = -(thickness - 1); dc <= thickness - 1; ++dc) {
          const int rr = r + dr, cc = c + dc;
          if (rr >= 0 && cc >= 0 && rr < rows && cc < cols && labels.at<std::int32_t>(rr, cc) == l)
            canvas.at<cv::Vec3b>(rr, cc) = colour;
        }
    }
  }

  // Label numbers at the centroids, white on a dark outline, sized with the grain.
  for (const Grain& g : s.table.grains) {
    const double diameter_px = g.shape.equivalent_diameter / s.pixel_size;
    if (diameter_px < 10.0) continue;
    const double scale = std::clamp(diameter_px / 60.0, 0.3, 1.2);
    const std::string text = std::to_string(g.label);
    int baseline = 0;
    const int weight = scale > 0.7 ? 2 : 1;
    const cv::Size size = cv::getTextSize(text, cv::FONT_HERSHEY_SIMPLEX, scale, weight, &baseline);
    const cv::Point at(static_cast<int>(std::lround(g.centroid_col)) - size.width / 2,
                       static_cast<int>(std::lround(g.centroid_row)) + size.height / 2);
    cv::putText(canvas, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), weight + 2,
                cv::LINE_AA);
    cv::putText(canvas, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(255, 255, 255),
                weight, cv::LINE_AA);
  }

  // Caption strip.
  std::vector<double> d;
  for (const Grain& g : s.table.grains) d.push_back(g.shape.equivalent_diameter);
  std::sort(d.begin(), d.end());
  const double median_um = d.empty() ? 0.0 : 1e6 * d[d.size() / 2];
  std::vector<std::string> lines{
      fmt::format("{} grains, median equivalent diameter {:.4g} \u00b5m, pixel {:.4g} \u00b5m",
                  s.table.grains.size(), median_um, 1e6 * s.pixel_size)};
  if (s.table.dropped_small + s.table.dropped_border > 0)
    lines.push_back(
        fmt::format("red: dropped grains ({} under the minimum area, {} cut by the border)",
                    s.table.dropped_small, s.table.dropped_border));
  // Text scaled with the image, shrunk until the widest line fits.
  double scale = std::clamp(cols / 1400.0, 0.3, 1.5);
  auto widest = [&](double sc) {
    int w = 0;
    for (const std::string& l : lines) w = std::max(w, analysis::label_extent(l, sc).width);
    return w;
  };
  while (scale > 0.2 && widest(scale) > cols - 12) scale *= 0.9;
  const int line_height = static_cast<int>(std::lround(32 * scale)) + 6;
  const int strip = line_height * static_cast<int>(lines.size()) + 6;
  cv::Mat out(rows + strip, cols, CV_8UC3, cv::Scalar(32, 32, 32));
  canvas.copyTo(out(cv::Rect(0, 0, cols, rows)));
  for (std::size_t k = 0; k < lines.size(); ++k)
    analysis::draw_label(out, lines[k], cv::Point(6, rows + 3 + static_cast<int>(k) * line_height),
                         scale,
                         k == 0 ? analysis::Rgb{255, 255, 255} : analysis::Rgb{255, 120, 120});
  return out;
}

void write_preview(const cv::Mat& preview, const std::string& path) {
  bool ok = false;
  try {
    ok = cv::imwrite(path, preview);
  } catch (const cv::Exception& e) {
    throw SegmentInputError(fmt::format("{}: cannot write the preview: {}", path, e.what()));
  }
  if (!ok)
    throw SegmentInputError(fmt::format(
        "{}: cannot write the preview (is the folder there and writable, and the extension .png?)",
        path));
}

}  // namespace fragmpm::pipeline
