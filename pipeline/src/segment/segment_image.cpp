#include "fragmpm/pipeline/segment_image.hpp"

#include <fmt/format.h>

#include <filesystem>
#include <fstream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

namespace fragmpm::pipeline {

namespace {

std::string rect_text(const cv::Rect& r) {
  return fmt::format("{},{},{},{}", r.x, r.y, r.width, r.height);
}

}  // namespace

LoadedImage prepare_image(const cv::Mat& image, const std::string& name,
                          const std::optional<cv::Rect>& crop) {
  if (image.empty())
    throw SegmentInputError(fmt::format("{}: the image is empty (0 pixels)", name));
  if (image.dims != 2 || image.rows < 2 || image.cols < 2)
    throw SegmentInputError(
        fmt::format("{}: the image is {} × {} pixels; need at least 2 × 2 pixels to find grains",
                    name, image.cols, image.rows));
  LoadedImage out;
  out.path = name;
  out.full_size = image.size();
  out.window = cv::Rect(0, 0, image.cols, image.rows);
  if (crop) {
    const cv::Rect& c = *crop;
    if (c.width < 2 || c.height < 2)
      throw SegmentInputError(fmt::format(
          "{}: crop window {} (x,y,w,h) must be at least 2 × 2 pixels", name, rect_text(c)));
    if (c.x < 0 || c.y < 0 || c.x + c.width > image.cols || c.y + c.height > image.rows)
      throw SegmentInputError(
          fmt::format("{}: crop window {} (x,y,w,h) is not inside the image of {} × {} pixels",
                      name, rect_text(c), image.cols, image.rows));
    out.window = c;
  }
  out.image = image(out.window).clone();
  out.grey = to_grey(out.image);
  return out;
}

LoadedImage load_image(const std::string& path, const std::optional<cv::Rect>& crop) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (path.empty()) throw SegmentInputError("no image file given");
  if (!fs::exists(path, ec)) throw SegmentInputError(fmt::format("{}: no such file", path));
  if (!fs::is_regular_file(path, ec))
    throw SegmentInputError(fmt::format("{}: not a regular file", path));
  if (std::ifstream probe(path, std::ios::binary); !probe.good())
    throw SegmentInputError(fmt::format("{}: cannot open the file for reading", path));
  if (fs::file_size(path, ec) == 0)
    throw SegmentInputError(fmt::format("{}: the file is empty (0 bytes)", path));
  // ANYDEPTH keeps 16-bit samples, ANYCOLOR keeps grey images single-channel; EXIF orientation of
  // photographs is applied.
  cv::Mat image;
  try {
    image = cv::imread(path, cv::IMREAD_ANYDEPTH | cv::IMREAD_ANYCOLOR);
  } catch (const cv::Exception& e) {
    throw SegmentInputError(fmt::format("{}: cannot decode the image: {}", path, e.what()));
  }
  if (image.empty())
    throw SegmentInputError(fmt::format(
        "{}: cannot read the image: not a PNG, TIFF, BMP or JPEG file OpenCV can decode, or the "
        "file is corrupt",
        path));
  return prepare_image(image, path, crop);
}

cv::Mat to_grey(const cv::Mat& image) {
  cv::Mat grey;
  switch (image.channels()) {
    case 1:
      grey = image.clone();
      break;
    case 3:
      cv::cvtColor(image, grey, cv::COLOR_BGR2GRAY);
      break;
    case 4:
      cv::cvtColor(image, grey, cv::COLOR_BGRA2GRAY);
      break;
    default:
      cv::extractChannel(image, grey, 0);
      break;  // grey + alpha: keep the grey channel
  }
  return grey;
}

double WorkingImage::working_level(double image_level) const {
  const double v = (image_level - lo) * 255.0 / (hi - lo);
  return inverted ? 255.0 - v : v;
}

WorkingImage working_image(const cv::Mat& grey, const PreprocessOptions& options) {
  WorkingImage w;
  if (grey.depth() == CV_8U) {
    w.image = grey.clone();
  } else {
    double lo = 0.0, hi = 0.0;
    cv::minMaxLoc(grey, &lo, &hi);
    if (hi <= lo) hi = lo + 1.0;  // uniform image; the threshold step reports it
    w.lo = lo;
    w.hi = hi;
    grey.convertTo(w.image, CV_8U, 255.0 / (hi - lo), -lo * 255.0 / (hi - lo));
  }
  if (options.invert) {
    cv::bitwise_not(w.image, w.image);
    w.inverted = true;
  }
  const int r = std::max(1, options.denoise_radius);
  switch (options.denoise) {
    case DenoiseMethod::none:
      break;
    case DenoiseMethod::median:
      cv::medianBlur(w.image, w.image, 2 * r + 1);
      break;
    case DenoiseMethod::gaussian:
      cv::GaussianBlur(w.image, w.image, cv::Size(0, 0), static_cast<double>(r));
      break;
    case DenoiseMethod::bilateral: {
      // Edge-preserving: smooths within grains without blurring their outlines.
      cv::Mat out;
      cv::bilateralFilter(w.image, out, 2 * r + 1, 30.0, static_cast<double>(r));
      w.image = out;
      break;
    }
  }
  if (options.gap_radius > 0) {
    // Black top-hat: closing − image is large only in dark features narrower than the disk.
    cv::Mat closed;
    const int g = options.gap_radius;
    cv::morphologyEx(w.image, closed, cv::MORPH_CLOSE,
                     cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * g + 1, 2 * g + 1)));
    w.image = 255 - (closed - w.image);
    w.gaps = true;
  }
  if (options.equalize) {
    auto clahe = cv::createCLAHE(2.0, cv::Size(8, 8));
    clahe->apply(w.image, w.image);
  }
  return w;
}

}  // namespace fragmpm::pipeline
