#pragma once
// Options of `fragmpm segment` (docs/design.md) and the error raised for bad segmentation input.
// Lengths in pixels unless the name says otherwise; the pixel size converts to SI.
#include <cstdint>
#include <opencv2/core/types.hpp>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace fragmpm::pipeline {

/// Bad input to the segmentation: missing or unreadable file, degenerate image, impossible option.
/// The message names the file (and pixel or option) and what was expected; the CLI exits with 2.
struct SegmentInputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// What the input image holds.
enum class InputKind {
  grey,     ///< a micrograph: grey or colour intensities, thresholded into grains
  classes,  ///< a class mask: grain class(es), boundary class(es), everything else background
  labels,   ///< a label image: every 4-connected patch of one non-zero value is a grain
};

enum class ThresholdMethod { otsu, triangle, adaptive, fixed };
enum class DenoiseMethod { none, median, gaussian, bilateral };

/// Turning a grey image into an 8-bit working image (order: stretch, invert, denoise, gap
/// detection, equalise).
struct PreprocessOptions {
  bool invert = false;  ///< grains darker than the background
  DenoiseMethod denoise = DenoiseMethod::none;
  int denoise_radius = 2;  ///< [px] half-width of the filter window (σ for gaussian)
  /// [px] 0 = off. For packed grains of any brightness separated by dark gaps (photographs of
  /// sand and gravel): the working image becomes 255 minus the black top-hat with a disk of this
  /// radius, so features darker than their surroundings and narrower than about twice the radius
  /// (the gaps) are dark and everything broader (the grains, bright or dark) is bright.
  int gap_radius = 0;
  bool equalize = false;  ///< CLAHE contrast equalisation
};

struct ThresholdOptions {
  ThresholdMethod method = ThresholdMethod::otsu;
  /// fixed: grey level in the image's own units (0–255 for 8-bit, 0–65535 for 16-bit); grains are
  /// the pixels brighter than it (darker with --invert).
  double level = 0.0;
  int adaptive_block = 51;  ///< adaptive: odd window width [px] of the local mean
  double adaptive_offset =
      5.0;  ///< adaptive: a grain pixel exceeds the local mean by more than this (8-bit levels)
};

/// Morphological clean-up of the thresholded mask.
struct CleanupOptions {
  int open_radius = 1;   ///< [px] opening removes specks and thin bridges; 0 = off
  int close_radius = 0;  ///< [px] closing fills thin cracks; 0 = off
  /// Before splitting, background regions enclosed by grain and no larger than this [px] are filled
  /// (specks and pits inside grains would otherwise split them); larger ones may be pores between
  /// touching grains and are kept. 0 = off.
  std::int64_t max_hole_area = 100;
  /// After splitting, background regions enclosed by one single grain become part of it.
  bool fill_holes = true;
};

/// Splitting touching grains: marker-controlled watershed on the Euclidean distance transform.
struct SplitOptions {
  bool enabled = true;
  /// [px] a marker is a maximum of the distance map within this radius. Small values find every
  /// grain; the neck criterion then merges the pieces of one grain.
  double marker_spacing = 3.0;
  /// Two neighbouring pieces stay apart only when the neck between them (distance-map value on
  /// their shared boundary) is narrower than this fraction of the smaller piece's inscribed
  /// radius; wider necks are merged back. 1 splits at every marker, 0 never splits.
  double neck_ratio = 0.65;
};

/// Class-mask input (InputKind::classes), e.g. the sandstone mask: 0 pore, 1 grain, 2 boundary.
struct ClassMaskOptions {
  std::vector<int> grain_classes{1};
  std::vector<int> boundary_classes{2};
  /// Boundary pixels join the nearest grain (grains that touch end up touching); otherwise they
  /// become background.
  bool boundary_to_grains = true;
};

struct SegmentOptions {
  std::string image_path;
  double pixel_size = 0.0;       ///< [m], must be > 0
  std::optional<cv::Rect> crop;  ///< window x, y, w, h in pixels of the input image
  InputKind input = InputKind::grey;
  PreprocessOptions preprocess;
  ThresholdOptions threshold;
  CleanupOptions cleanup;
  SplitOptions split;
  ClassMaskOptions classes;
  std::int64_t min_area = 16;  ///< [px] grains with fewer pixels are dropped
  /// [px] 0 = off. After splitting (and dropping grains under min_area), grains grow into the
  /// background by up to this distance, each pixel joining the nearest grain, never merging two:
  /// for packed grains whose dark gaps are boundaries between them rather than pores.
  double grow = 0.0;
  bool drop_border = false;  ///< drop grains cut by the (cropped) image border
  /// Grey-level band limits, ascending, in the image's own units: a grain whose mean grey level is
  /// below phase_bands[0] is phase 0, between [0] and [1] phase 1, …; empty = one phase.
  std::vector<double> phase_bands;
};

}  // namespace fragmpm::pipeline
