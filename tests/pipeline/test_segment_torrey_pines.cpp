// The Torrey Pines beach photograph against its hand-checked mask: grain count and
// median equivalent diameter within 10 %. The photograph is hard for a threshold — pebbles from
// near-black to beige, packed with dark gaps — so it uses the packed-grain recipe documented in
// images/PROVENANCE.md: gap detection, median filter, fine watershed markers with a permissive neck
// ratio, and growth of the grains into the gaps.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "fragmpm/pipeline/segment.hpp"

namespace fp = fragmpm::pipeline;

namespace {

double median_diameter_px(const fp::Segmentation& s) {
  std::vector<double> d;
  for (const fp::Grain& g : s.table.grains) d.push_back(g.shape.equivalent_diameter / s.pixel_size);
  std::sort(d.begin(), d.end());
  return d[d.size() / 2];
}

const std::string kImages = std::string(FRAGMPM_SOURCE_DIR) + "/images/";

fp::SegmentOptions torrey_pines_recipe() {
  fp::SegmentOptions o;
  o.image_path = kImages + "torrey_pines_beach_image.jpg";
  o.pixel_size = 1e-6;  // not stated by the source; the comparison is in pixels
  o.preprocess.denoise = fp::DenoiseMethod::median;
  o.preprocess.denoise_radius = 3;
  o.preprocess.gap_radius = 9;
  o.cleanup.open_radius = 3;
  o.split.neck_ratio = 0.9;
  o.split.marker_spacing = 10.0;
  o.grow = 6.0;
  return o;
}

}  // namespace

TEST(SegmentTorreyPines, CountAndMedianSizeWithinTenPercentOfTheMask) {
  fp::SegmentOptions truth_options;
  truth_options.image_path = kImages + "torrey_pines_beach_mask.png";
  truth_options.pixel_size = 1e-6;
  truth_options.input = fp::InputKind::classes;  // 0 background, 1 grain, 2 boundary line
  const fp::Segmentation truth = fp::segment(truth_options);
  const fp::Segmentation found = fp::segment(torrey_pines_recipe());

  const double n_truth = static_cast<double>(truth.table.grains.size());
  const double n_found = static_cast<double>(found.table.grains.size());
  const double d_truth = median_diameter_px(truth), d_found = median_diameter_px(found);
  std::printf(
      "Torrey Pines: %zu grains (mask %zu, %+.1f %%), median equivalent diameter %.2f px "
      "(mask %.2f px, %+.1f %%)\n",
      found.table.grains.size(), truth.table.grains.size(), 100.0 * (n_found / n_truth - 1.0),
      d_found, d_truth, 100.0 * (d_found / d_truth - 1.0));
  EXPECT_NEAR(n_found / n_truth, 1.0, 0.10);
  EXPECT_NEAR(d_found / d_truth, 1.0, 0.10);
}
