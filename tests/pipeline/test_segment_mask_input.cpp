// Already-segmented input: class masks with a boundary class and label images.
#include <gtest/gtest.h>

#include <algorithm>
#include <opencv2/core.hpp>
#include <string>

#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_mask_input.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"
#include "segment_test_support.hpp"

namespace fp = fragmpm::pipeline;
using fp::testing::micrometre_options;

namespace {

/// Class mask in the style of the sandstone and Torrey Pines masks: 0 background, 1 grain,
/// 2 boundary on every grain pixel next to another grain or to the background.
cv::Mat class_mask(const cv::Mat& truth) {
  cv::Mat classes = cv::Mat::zeros(truth.size(), CV_8U);
  for (int r = 0; r < truth.rows; ++r)
    for (int c = 0; c < truth.cols; ++c) {
      const int l = truth.at<int>(r, c);
      if (l == 0) continue;
      bool edge = false;
      for (const auto& [dr, dc] :
           {std::pair{-1, 0}, std::pair{1, 0}, std::pair{0, -1}, std::pair{0, 1}}) {
        const int rr = std::clamp(r + dr, 0, truth.rows - 1),
                  cc = std::clamp(c + dc, 0, truth.cols - 1);
        edge = edge || truth.at<int>(rr, cc) != l;
      }
      classes.at<unsigned char>(r, c) = edge ? 2 : 1;
    }
  return classes;
}

std::int64_t truth_pixels(const fp::SyntheticImage& d, std::size_t k) {
  return cv::countNonZero(d.truth == static_cast<int>(k) + 1);
}

}  // namespace

TEST(SegmentMaskInput, ClassMaskBoundariesGoBackToTheirGrains) {
  // Touching pairs: the boundary line between two grains is one pixel on each side, so giving
  // each boundary pixel to the nearest grain restores the ground truth exactly.
  const fp::SyntheticImage d = fp::synthetic_touching_pairs();
  fp::SegmentOptions o = micrometre_options("pairs mask");
  o.input = fp::InputKind::classes;
  const fp::Segmentation s = fp::segment(class_mask(d.truth), o);
  ASSERT_EQ(s.table.grains.size(), 12u);
  for (std::size_t k = 0; k < d.grains.size(); ++k) {
    const int label =
        s.table.labels.at<int>(static_cast<int>(d.grains[k].cy), static_cast<int>(d.grains[k].cx));
    ASSERT_GT(label, 0);
    EXPECT_EQ(s.table.grains[static_cast<std::size_t>(label - 1)].pixels, truth_pixels(d, k))
        << "grain " << k;
  }
  // Boundary as background: only the interiors remain, every grain smaller by its outline.
  o.classes.boundary_to_grains = false;
  const fp::Segmentation inner = fp::segment(class_mask(d.truth), o);
  ASSERT_EQ(inner.table.grains.size(), 12u);
  for (const fp::Grain& g : inner.table.grains) {
    const int truth_label =
        d.truth.at<int>(static_cast<int>(g.centroid_row), static_cast<int>(g.centroid_col));
    EXPECT_LT(g.pixels, truth_pixels(d, static_cast<std::size_t>(truth_label - 1)));
  }
}

TEST(SegmentMaskInput, SeveralGrainClassesAndPhases) {
  // Grain classes 1 and 3 (two minerals), boundary 2; phases from the class value.
  const fp::SyntheticImage d = fp::synthetic_disks();
  cv::Mat classes = class_mask(d.truth);
  for (int r = 0; r < classes.rows; ++r)
    for (int c = 0; c < classes.cols; ++c)
      if (classes.at<unsigned char>(r, c) == 1 && d.truth.at<int>(r, c) % 2 == 0)
        classes.at<unsigned char>(r, c) = 3;
  fp::SegmentOptions o = micrometre_options("two minerals");
  o.input = fp::InputKind::classes;
  o.classes.grain_classes = {1, 3};
  o.phase_bands = {2.0};
  o.cleanup.fill_holes = false;
  const fp::Segmentation s = fp::segment(classes, o);
  ASSERT_EQ(s.table.grains.size(), 12u);
  for (const fp::Grain& g : s.table.grains) {
    const int t =
        d.truth.at<int>(static_cast<int>(g.centroid_row), static_cast<int>(g.centroid_col));
    EXPECT_EQ(g.phase, t % 2 == 0 ? 1 : 0) << "truth grain " << t;
  }
}

TEST(SegmentMaskInput, LabelImageKeepsGrainsAndSplitsRepeatedLabels) {
  const fp::SyntheticImage d = fp::synthetic_irregular(4);
  cv::Mat labels16;
  d.truth.convertTo(labels16, CV_16U);
  fp::SegmentOptions o = micrometre_options("labels");
  o.input = fp::InputKind::labels;
  const fp::Segmentation s = fp::segment(labels16, o);
  ASSERT_EQ(s.table.grains.size(), 12u);
  for (std::size_t k = 0; k < d.grains.size(); ++k) {
    const int label =
        s.table.labels.at<int>(static_cast<int>(d.grains[k].cy), static_cast<int>(d.grains[k].cx));
    ASSERT_GT(label, 0);
    EXPECT_EQ(s.table.grains[static_cast<std::size_t>(label - 1)].pixels, truth_pixels(d, k));
  }
  // One value used for two separate patches gives two grains.
  cv::Mat twice = cv::Mat::zeros(20, 20, CV_16U);
  twice(cv::Rect(2, 2, 5, 5)).setTo(9);
  twice(cv::Rect(12, 12, 5, 5)).setTo(9);
  o.min_area = 1;
  EXPECT_EQ(fp::segment(twice, o).table.grains.size(), 2u);
}

TEST(SegmentMaskInput, SandstoneWindowFromImages) {
  fp::SegmentOptions o =
      micrometre_options(std::string(FRAGMPM_SOURCE_DIR) + "/images/miocene_sandstone_window.png");
  o.input = fp::InputKind::classes;
  const fp::Segmentation s = fp::segment(o);
  EXPECT_EQ(s.input.grey.cols, 800);
  EXPECT_EQ(s.input.grey.rows, 600);
  EXPECT_EQ(s.table.grains.size(), 51u);
  // Boundary lines given to the grains: grains touch, and background (pores) remains.
  const double grain_fraction =
      static_cast<double>(cv::countNonZero(s.table.labels)) / (800.0 * 600.0);
  EXPECT_GT(grain_fraction, 0.5);
  EXPECT_LT(grain_fraction, 0.95);
}

TEST(SegmentMaskInput, ClearMessagesForWrongMasks) {
  fp::SegmentOptions o = micrometre_options("photo.png");
  o.input = fp::InputKind::classes;
  cv::Mat no_grain(10, 10, CV_8U, cv::Scalar(0));
  no_grain(cv::Rect(2, 2, 3, 3)).setTo(7);
  try {
    fp::segment(no_grain, o);
    FAIL() << "expected SegmentInputError";
  } catch (const fp::SegmentInputError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("photo.png"), std::string::npos) << m;
    EXPECT_NE(m.find("0, 7"), std::string::npos) << m;
  }
  o.classes.boundary_classes = {1};
  EXPECT_THROW(fp::segment(no_grain, o), fp::SegmentInputError);
  cv::Mat all_grain(10, 10, CV_8U, cv::Scalar(1));
  o.classes.boundary_classes = {2};
  EXPECT_THROW(fp::segment(all_grain, o), fp::SegmentInputError);
  o.input = fp::InputKind::labels;
  EXPECT_THROW(fp::segment(cv::Mat(10, 10, CV_16U, cv::Scalar(0)), o), fp::SegmentInputError);
  EXPECT_THROW(fp::segment(cv::Mat(10, 10, CV_16U, cv::Scalar(4)), o), fp::SegmentInputError);
}
