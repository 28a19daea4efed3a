#pragma once
// Helpers shared by the segmentation tests: matching segmented grains to synthetic ground truth.
#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <string>

#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"

namespace fragmpm::pipeline::testing {

/// Every truth grain's centre lies in a distinct segmented grain whose area is within `rel_tol`
/// of the analytic area (pixel size 1 µm assumed by the caller's options).
inline void expect_matches_truth(const Segmentation& s, const SyntheticImage& truth, double rel_tol,
                                 const std::string& what) {
  ASSERT_EQ(s.table.grains.size(), truth.grains.size()) << what << ": grain count";
  std::set<int> used;
  for (std::size_t k = 0; k < truth.grains.size(); ++k) {
    const SyntheticGrain& t = truth.grains[k];
    const int col = static_cast<int>(std::floor(t.cx)), row = static_cast<int>(std::floor(t.cy));
    const int label = s.table.labels.at<int>(std::clamp(row, 0, s.table.labels.rows - 1),
                                             std::clamp(col, 0, s.table.labels.cols - 1));
    ASSERT_GT(label, 0) << what << ": truth grain " << k << " centre is background";
    EXPECT_TRUE(used.insert(label).second) << what << ": truth grains share label " << label;
    const double area_px = s.table.grains[static_cast<std::size_t>(label - 1)].shape.area /
                           (s.pixel_size * s.pixel_size);
    EXPECT_NEAR(area_px / t.area, 1.0, rel_tol)
        << what << ": grain " << k << " area " << area_px << " px² vs " << t.area;
  }
}

inline SegmentOptions micrometre_options(const std::string& name) {
  SegmentOptions o;
  o.image_path = name;
  o.pixel_size = 1e-6;
  return o;
}

}  // namespace fragmpm::pipeline::testing
