#pragma once
// Label images from masks and splitting of touching grains: marker-controlled
// watershed on the Euclidean distance transform, with markers merged back across wide necks.
//
// OpenCV's cv::watershed ranks pixels by the colour difference to their neighbour rather than by
// height, so it cannot flood a distance map; the priority flood here does (Meyer's algorithm).
#include <cstdint>
#include <opencv2/core/mat.hpp>

#include "fragmpm/pipeline/segment_options.hpp"

namespace fragmpm::pipeline {

/// 4-connected components of the non-zero pixels of `mask` (CV_8UC1), as CV_32SC1 labels 1..N in
/// raster order of each component's first pixel; 0 = background. 4-connectivity keeps grains that
/// meet only at a corner (e.g. across a one-pixel diagonal boundary line) apart.
cv::Mat connected_labels(const cv::Mat& mask);

/// Grows the labels of `seeds` (CV_32SC1, > 0 = seed) into the non-zero pixels of `allowed`
/// (CV_8UC1) through 4-neighbours. With a `height` map (CV_32FC1) higher pixels are reached first
/// (a watershed of −height); without one (empty Mat) every pixel joins the nearest seed in
/// 4-connected steps (breadth-first, ties to the earlier seed in raster order). Pixels of
/// `allowed` not connected to any seed stay 0.
cv::Mat flood_labels(const cv::Mat& seeds, const cv::Mat& allowed,
                     const cv::Mat& height = cv::Mat());

/// Splits a binary grain mask (CV_8UC1) into grains: markers are maxima of the distance transform
/// within `marker_spacing` pixels, the flood follows the distance map, and neighbouring pieces are
/// merged back when the neck between them is wider than `neck_ratio` times the smaller piece's
/// inscribed radius (largest distance value). Returns compact CV_32SC1 labels; with
/// options.enabled false, just the connected components.
cv::Mat split_touching_grains(const cv::Mat& mask, const SplitOptions& options);

/// Background regions (4-connected, not touching the image border) whose neighbours all belong to a
/// single grain are given to that grain. `labels` is CV_32SC1, modified in place.
void fill_enclosed_holes(cv::Mat& labels);

/// Renumbers labels > 0 to 1..N in raster order of first appearance; returns N.
int compact_labels(cv::Mat& labels);

/// Sets the labels of grains with fewer than `min_area` pixels to 0, marks their pixels 255 in
/// `removed` (CV_8UC1, allocated if empty) and returns how many grains were removed.
std::int64_t remove_small_grains(cv::Mat& labels, std::int64_t min_area, cv::Mat& removed);

/// Grows every grain into the background pixels within Euclidean distance `radius` [px] of some
/// grain; each such pixel joins the grain nearest to it in 4-connected steps, so grains never
/// merge.
void grow_labels(cv::Mat& labels, double radius);

}  // namespace fragmpm::pipeline
