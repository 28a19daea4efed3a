#include "fragmpm/pipeline/segment.hpp"

#include <fmt/format.h>

#include <cmath>
#include <limits>
#include <opencv2/core.hpp>
#include <utility>

#include "fragmpm/pipeline/segment_mask_input.hpp"
#include "fragmpm/pipeline/segment_threshold.hpp"
#include "fragmpm/pipeline/segment_watershed.hpp"

namespace fragmpm::pipeline {

namespace {

const char* method_name(ThresholdMethod m) {
  switch (m) {
    case ThresholdMethod::otsu:
      return "otsu";
    case ThresholdMethod::triangle:
      return "triangle";
    case ThresholdMethod::adaptive:
      return "adaptive";
    case ThresholdMethod::fixed:
      return "fixed";
  }
  return "?";
}

// Inverse of WorkingImage::working_level.
double image_level(const WorkingImage& w, double working) {
  const double v = w.inverted ? 255.0 - working : working;
  return w.lo + v * (w.hi - w.lo) / 255.0;
}

}  // namespace

void validate_segment_options(const SegmentOptions& o) {
  if (!(o.pixel_size > 0.0) || !std::isfinite(o.pixel_size))
    throw SegmentInputError(
        fmt::format("--pixel-size must be a positive length, got {} m", o.pixel_size));
  if (o.min_area < 0)
    throw SegmentInputError(fmt::format("--min-area must be ≥ 0 pixels, got {}", o.min_area));
  for (std::size_t k = 1; k < o.phase_bands.size(); ++k)
    if (!(o.phase_bands[k] > o.phase_bands[k - 1]))
      throw SegmentInputError(
          fmt::format("--phase-bands must be strictly ascending grey levels, got {} after {}",
                      o.phase_bands[k], o.phase_bands[k - 1]));
  if (o.preprocess.denoise != DenoiseMethod::none && o.preprocess.denoise_radius < 1)
    throw SegmentInputError(
        fmt::format("--denoise-radius must be ≥ 1 pixel, got {}", o.preprocess.denoise_radius));
  if (o.cleanup.open_radius < 0 || o.cleanup.close_radius < 0)
    throw SegmentInputError("--open and --close radii must be ≥ 0 pixels");
  if (o.cleanup.max_hole_area < 0)
    throw SegmentInputError(
        fmt::format("--max-hole-area must be ≥ 0 pixels, got {}", o.cleanup.max_hole_area));
  if (o.split.enabled && !(o.split.marker_spacing >= 1.0))
    throw SegmentInputError(
        fmt::format("--marker-spacing must be ≥ 1 pixel, got {}", o.split.marker_spacing));
  if (!(o.split.neck_ratio >= 0.0 && o.split.neck_ratio <= 1.0))
    throw SegmentInputError(
        fmt::format("--neck-ratio must lie in [0, 1], got {}", o.split.neck_ratio));
  if (o.preprocess.gap_radius < 0)
    throw SegmentInputError(
        fmt::format("--gaps must be ≥ 0 pixels, got {}", o.preprocess.gap_radius));
  if (o.preprocess.gap_radius > 0 && o.threshold.method == ThresholdMethod::fixed)
    throw SegmentInputError(
        "--level (fixed threshold) cannot be combined with --gaps: the gap image no longer has the "
        "image's grey levels; use --threshold otsu or triangle");
  if (!(o.grow >= 0.0) || !std::isfinite(o.grow))
    throw SegmentInputError(fmt::format("--grow must be ≥ 0 pixels, got {}", o.grow));
  if (o.threshold.method == ThresholdMethod::adaptive &&
      (o.threshold.adaptive_block < 3 || o.threshold.adaptive_block % 2 == 0))
    throw SegmentInputError(fmt::format("--block must be an odd number of pixels ≥ 3, got {}",
                                        o.threshold.adaptive_block));
}

Segmentation segment(LoadedImage input, const SegmentOptions& options) {
  validate_segment_options(options);
  Segmentation s;
  s.pixel_size = options.pixel_size;
  s.kind = options.input;
  s.threshold_level = std::numeric_limits<double>::quiet_NaN();
  const std::string& name = input.path;
  cv::Mat labels;
  switch (options.input) {
    case InputKind::grey: {
      const WorkingImage work = working_image(input.grey, options.preprocess);
      const ThresholdResult thr = threshold_grains(work, options.threshold, name);
      // With gap detection the level is on the gap image's own 0–255 scale.
      if (!std::isnan(thr.level))
        s.threshold_level = work.gaps ? thr.level : image_level(work, thr.level);
      const cv::Mat mask = clean_mask(thr.mask, options.cleanup);
      const std::string how =
          std::isnan(thr.level)
              ? fmt::format("adaptive threshold, block {} px, offset {}",
                            options.threshold.adaptive_block, options.threshold.adaptive_offset)
              : fmt::format("{} threshold at {} level {:.6g}",
                            method_name(options.threshold.method), work.gaps ? "gap-image" : "grey",
                            s.threshold_level);
      check_mask_has_both(mask, name, how);
      labels = split_touching_grains(mask, options.split);
      break;
    }
    case InputKind::classes:
      labels = labels_from_classes(input.grey, options.classes, name);
      break;
    case InputKind::labels:
      labels = labels_from_label_image(input.grey, name);
      break;
  }
  if (options.cleanup.fill_holes) fill_enclosed_holes(labels);
  // Small grains go before growing, or every speck would grow into a grain.
  cv::Mat removed;
  std::int64_t removed_small = 0;
  if (options.grow > 0.0) {
    removed_small = remove_small_grains(labels, options.min_area, removed);
    grow_labels(labels, options.grow);
  }
  s.table = measure_grains(labels, input.grey, options.pixel_size, options.min_area,
                           options.drop_border, options.phase_bands);
  if (removed_small > 0) {
    s.table.dropped_small += removed_small;
    const cv::Mat still_background = removed & (s.table.labels == 0);
    cv::bitwise_or(s.table.dropped, still_background, s.table.dropped);
  }
  if (s.table.grains.empty())
    throw SegmentInputError(fmt::format(
        "{}: no grains left: {} smaller than --min-area {} px{}", name, s.table.dropped_small,
        options.min_area,
        options.drop_border
            ? fmt::format(", {} cut by the image border (--drop-border)", s.table.dropped_border)
            : std::string()));
  s.input = std::move(input);
  return s;
}

Segmentation segment(const cv::Mat& image, const SegmentOptions& options) {
  validate_segment_options(options);
  return segment(
      prepare_image(image, options.image_path.empty() ? "image" : options.image_path, options.crop),
      options);
}

Segmentation segment(const SegmentOptions& options) {
  validate_segment_options(options);
  return segment(load_image(options.image_path, options.crop), options);
}

}  // namespace fragmpm::pipeline
