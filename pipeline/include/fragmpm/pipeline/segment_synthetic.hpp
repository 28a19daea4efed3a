#pragma once
// Synthetic micrographs with known answers: bright grains of analytic shape
// on a dark background, with their ground-truth labels and analytic areas. Used by the tests and by
// the `fragmpm_make_images` tool that writes images/synthetic/.
#include <cstdint>
#include <opencv2/core/mat.hpp>
#include <string>
#include <vector>

namespace fragmpm::pipeline {

struct SyntheticGrain {
  double cx = 0.0, cy = 0.0;  ///< centre [px] in image coordinates (column, row)
  double area = 0.0;          ///< analytic area [px²]
  std::int32_t phase = 0;     ///< intended phase (two-phase image only)
};

struct SyntheticImage {
  std::string name;
  cv::Mat image;  ///< CV_8UC1, grains bright on a dark background
  cv::Mat truth;  ///< CV_32SC1 ground truth: grains[k] has label k + 1, 0 = background
  std::vector<SyntheticGrain> grains;
};

/// Grey levels of the synthetic images.
inline constexpr int kSyntheticBackground = 60;
inline constexpr int kSyntheticGrain = 190;

/// 640 × 480: twelve separate disks of radii 10 … 42 px on a 4 × 3 grid (area π r²).
SyntheticImage synthetic_disks();

/// 640 × 480: twelve separate irregular (star-shaped) grains r(θ) = r0 (1 + Σ_k a_k cos(kθ + φ_k)),
/// k = 2 … 4, |a_k| ≤ 0.08, drawn from `seed`; area π r0² (1 + ½ Σ a_k²).
SyntheticImage synthetic_irregular(std::uint32_t seed);

/// 640 × 480: six pairs of overlapping disks (twelve grains) whose necks are 0.3 – 0.55 of the
/// smaller radius. Ground truth splits each pair along the common chord (the radical axis); the
/// area of each piece is the disk minus its circular segment beyond the chord.
SyntheticImage synthetic_touching_pairs();

/// 640 × 480: six disks fully inside and five cut by the image border (truth areas are pixel
/// counts for the cut ones, π r² for the others).
SyntheticImage synthetic_border_disks();

/// 640 × 480: twelve disks, alternately of grey level 120 (phase 0) and 230 (phase 1), on 30.
SyntheticImage synthetic_two_phase();

/// Adds zero-mean Gaussian noise of standard deviation `sigma` grey levels (saturating), seeded.
void add_gaussian_noise(cv::Mat& image, double sigma, std::uint32_t seed);

/// 16-bit version of an 8-bit image: v16 = offset + gain · v8 (default maps 0…255 to 1000…52000).
cv::Mat to_16bit(const cv::Mat& image8, double gain = 200.0, double offset = 1000.0);

}  // namespace fragmpm::pipeline
