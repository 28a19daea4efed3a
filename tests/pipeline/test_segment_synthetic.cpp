// Segmentation of synthetic micrographs with known answers: exact counts, areas
// within 2 %, touching pairs split along their neck, noise, border option, inversion, thresholds.
#include <gtest/gtest.h>

#include <numbers>
#include <opencv2/core.hpp>

#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"
#include "segment_test_support.hpp"

namespace fp = fragmpm::pipeline;
using fp::testing::expect_matches_truth;
using fp::testing::micrometre_options;

TEST(SegmentSynthetic, DisksCountExactAndAreasWithinTwoPercent) {
  const fp::SyntheticImage d = fp::synthetic_disks();
  const fp::Segmentation s = fp::segment(d.image, micrometre_options("disks"));
  expect_matches_truth(s, d, 0.02, "disks");
  EXPECT_EQ(s.table.dropped_small, 0);
  // Otsu's level separates the two grey levels (grain pixels are those above it).
  EXPECT_GE(s.threshold_level, fp::kSyntheticBackground);
  EXPECT_LT(s.threshold_level, fp::kSyntheticGrain);
  for (const fp::Grain& g : s.table.grains)
    EXPECT_GT(g.shape.roundness, 0.95) << "grain " << g.label;
}

TEST(SegmentSynthetic, IrregularGrainsCountExactAndAreasWithinTwoPercent) {
  for (const std::uint32_t seed : {1u, 7u, 23u}) {
    const fp::SyntheticImage d = fp::synthetic_irregular(seed);
    const fp::Segmentation s = fp::segment(d.image, micrometre_options("irregular"));
    expect_matches_truth(s, d, 0.02, "irregular seed " + std::to_string(seed));
  }
}

TEST(SegmentSynthetic, TouchingPairsAreSplitAtTheirNecks) {
  const fp::SyntheticImage d = fp::synthetic_touching_pairs();
  const fp::Segmentation s = fp::segment(d.image, micrometre_options("pairs"));
  // The split follows the common chord: each piece within 2 % of disk minus its segment.
  expect_matches_truth(s, d, 0.02, "touching pairs");
  // Without splitting each pair is one grain.
  fp::SegmentOptions o = micrometre_options("pairs");
  o.split.enabled = false;
  EXPECT_EQ(fp::segment(d.image, o).table.grains.size(), 6u);
  // A neck ratio of 0 never keeps pieces apart.
  o.split.enabled = true;
  o.split.neck_ratio = 0.0;
  EXPECT_EQ(fp::segment(d.image, o).table.grains.size(), 6u);
}

TEST(SegmentSynthetic, WatershedDoesNotOversplitWithFineMarkers) {
  // Markers every pixel radius: the neck criterion alone must merge the pieces of each grain.
  const fp::SyntheticImage d = fp::synthetic_irregular(5);
  fp::SegmentOptions o = micrometre_options("irregular");
  o.split.marker_spacing = 1.0;
  expect_matches_truth(fp::segment(d.image, o), d, 0.02, "irregular, marker spacing 1");
}

TEST(SegmentSynthetic, NoiseIsToleratedWithDenoising) {
  // σ = 30 grey levels on a contrast of 130: Otsu on the raw image leaves specks and pits; a
  // median filter and the default clean-up give the exact answer.
  fp::SyntheticImage d = fp::synthetic_disks();
  fp::add_gaussian_noise(d.image, 30.0, 11);
  fp::SegmentOptions o = micrometre_options("noisy disks");
  o.preprocess.denoise = fp::DenoiseMethod::median;
  o.preprocess.denoise_radius = 2;
  expect_matches_truth(fp::segment(d.image, o), d, 0.02, "noisy disks, median");
  // A Gaussian blur rounds the outline of the smallest disks (r = 10, 13 px) by a few pixels.
  o.preprocess.denoise = fp::DenoiseMethod::gaussian;
  expect_matches_truth(fp::segment(d.image, o), d, 0.03, "noisy disks, gaussian");
  o.preprocess.denoise = fp::DenoiseMethod::bilateral;
  expect_matches_truth(fp::segment(d.image, o), d, 0.03, "noisy disks, bilateral");
  // Touching pairs under noise: every pair is still split; the noise moves the split line by a
  // pixel or two (pieces within 5 %), while each pair's total area stays within 2 %.
  fp::SyntheticImage pairs = fp::synthetic_touching_pairs();
  fp::add_gaussian_noise(pairs.image, 30.0, 12);
  o.preprocess.denoise = fp::DenoiseMethod::median;
  const fp::Segmentation s = fp::segment(pairs.image, o);
  expect_matches_truth(s, pairs, 0.05, "noisy touching pairs");
  for (std::size_t k = 0; k < pairs.grains.size(); k += 2) {
    double found = 0.0;
    for (std::size_t m = k; m < k + 2; ++m) {
      const int label = s.table.labels.at<int>(static_cast<int>(pairs.grains[m].cy),
                                               static_cast<int>(pairs.grains[m].cx));
      found += s.table.grains[static_cast<std::size_t>(label - 1)].shape.area / 1e-12;
    }
    EXPECT_NEAR(found / (pairs.grains[k].area + pairs.grains[k + 1].area), 1.0, 0.02)
        << "pair " << k / 2;
  }
}

TEST(SegmentSynthetic, BorderOptionDropsCutGrains) {
  const fp::SyntheticImage d = fp::synthetic_border_disks();
  fp::SegmentOptions o = micrometre_options("border");
  const fp::Segmentation all = fp::segment(d.image, o);
  expect_matches_truth(all, d, 0.02, "border disks kept");
  std::size_t cut = 0;
  for (const fp::Grain& g : all.table.grains) cut += g.touches_border;
  EXPECT_EQ(cut, 5u);
  o.drop_border = true;
  const fp::Segmentation inner = fp::segment(d.image, o);
  EXPECT_EQ(inner.table.grains.size(), 6u);
  EXPECT_EQ(inner.table.dropped_border, 5);
  for (const fp::Grain& g : inner.table.grains) EXPECT_FALSE(g.touches_border);
  EXPECT_GT(cv::countNonZero(inner.table.dropped), 0);
}

TEST(SegmentSynthetic, MinimumAreaDropsSmallGrains) {
  const fp::SyntheticImage d = fp::synthetic_disks();  // radii 10 … 42: the r = 10 disk has 314 px
  fp::SegmentOptions o = micrometre_options("disks");
  o.min_area = 600;  // drops r = 10 (314 px) and r = 13 (531 px)
  const fp::Segmentation s = fp::segment(d.image, o);
  EXPECT_EQ(s.table.grains.size(), 10u);
  EXPECT_EQ(s.table.dropped_small, 2);
}

TEST(SegmentSynthetic, InvertFindsDarkGrains) {
  const fp::SyntheticImage d = fp::synthetic_disks();
  cv::Mat dark = 255 - d.image;
  fp::SegmentOptions o = micrometre_options("dark disks");
  o.preprocess.invert = true;
  expect_matches_truth(fp::segment(dark, o), d, 0.02, "inverted");
}

TEST(SegmentSynthetic, ThresholdMethodsAgreeOnAClearImage) {
  const fp::SyntheticImage d = fp::synthetic_irregular(3);
  fp::SegmentOptions o = micrometre_options("irregular");
  o.threshold.method = fp::ThresholdMethod::triangle;
  expect_matches_truth(fp::segment(d.image, o), d, 0.02, "triangle");
  o.threshold.method = fp::ThresholdMethod::fixed;
  o.threshold.level = 125.0;
  const fp::Segmentation fixed = fp::segment(d.image, o);
  expect_matches_truth(fixed, d, 0.02, "fixed");
  EXPECT_DOUBLE_EQ(fixed.threshold_level, 125.0);
  // Adaptive: a pixel is grain when brighter than its 151-px local mean + 20.
  o.threshold.method = fp::ThresholdMethod::adaptive;
  o.threshold.adaptive_block = 151;
  o.threshold.adaptive_offset = -20.0;
  expect_matches_truth(fp::segment(d.image, o), d, 0.02, "adaptive");
  o.threshold.method = fp::ThresholdMethod::otsu;
  o.preprocess.equalize = true;
  expect_matches_truth(fp::segment(d.image, o), d, 0.02, "otsu after CLAHE");
}

TEST(SegmentSynthetic, SixteenBitImageGivesTheSameGrains) {
  const fp::SyntheticImage d = fp::synthetic_touching_pairs();
  cv::Mat deep = fp::to_16bit(d.image);  // 1000 … 52000
  fp::add_gaussian_noise(deep, 2000.0, 13);
  fp::SegmentOptions o = micrometre_options("16-bit pairs");
  const fp::Segmentation s = fp::segment(deep, o);
  expect_matches_truth(s, d, 0.02, "16-bit Otsu");
  // The level is reported in the image's own 16-bit units, between the two populations.
  EXPECT_GT(s.threshold_level, 1000.0 + 200.0 * fp::kSyntheticBackground);
  EXPECT_LT(s.threshold_level, 1000.0 + 200.0 * fp::kSyntheticGrain);
  // A fixed level is given in 16-bit units too.
  o.threshold.method = fp::ThresholdMethod::fixed;
  o.threshold.level = 1000.0 + 200.0 * 125.0;
  expect_matches_truth(fp::segment(deep, o), d, 0.02, "16-bit fixed");
}

TEST(SegmentSynthetic, PhasesFromGreyLevelBands) {
  const fp::SyntheticImage d = fp::synthetic_two_phase();
  fp::SegmentOptions o = micrometre_options("two phase");
  o.threshold.method = fp::ThresholdMethod::fixed;
  o.threshold.level = 75.0;  // between the background (30) and the darker phase (120)
  o.phase_bands = {175.0};
  const fp::Segmentation s = fp::segment(d.image, o);
  expect_matches_truth(s, d, 0.02, "two phase");
  for (const fp::SyntheticGrain& t : d.grains) {
    const int label = s.table.labels.at<int>(static_cast<int>(t.cy), static_cast<int>(t.cx));
    const fp::Grain& g = s.table.grains[static_cast<std::size_t>(label - 1)];
    EXPECT_EQ(g.phase, t.phase);
    EXPECT_NEAR(g.mean_grey, t.phase ? 230.0 : 120.0, 1e-9);
  }
}

TEST(SegmentSynthetic, CropSelectsAWindow) {
  // The window holds the top-left disk (centre 80, 80, r = 10) only.
  const fp::SyntheticImage d = fp::synthetic_disks();
  fp::SegmentOptions o = micrometre_options("disks");
  o.crop = cv::Rect(40, 40, 90, 80);
  const fp::Segmentation s = fp::segment(d.image, o);
  ASSERT_EQ(s.table.grains.size(), 1u);
  EXPECT_EQ(s.input.window, cv::Rect(40, 40, 90, 80));
  EXPECT_NEAR(s.table.grains[0].centroid_col, 40.0, 0.05);
  EXPECT_NEAR(s.table.grains[0].shape.area / 1e-12, std::numbers::pi * 100.0,
              0.02 * std::numbers::pi * 100.0);
}
