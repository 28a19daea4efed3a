#include "fragmpm/pipeline/segment_grains.hpp"

#include <algorithm>
#include <unordered_map>

namespace fragmpm::pipeline {

std::int32_t phase_of(double mean_grey, const std::vector<double>& bands) {
  return static_cast<std::int32_t>(std::upper_bound(bands.begin(), bands.end(), mean_grey) -
                                   bands.begin());
}

GrainTable measure_grains(const cv::Mat& raw_labels, const cv::Mat& grey, double pixel_size,
                          std::int64_t min_area, bool drop_border,
                          const std::vector<double>& phase_bands) {
  const std::vector<analysis::LabelRegion> regions =
      analysis::label_region_shapes(raw_labels, pixel_size);
  GrainTable table;
  std::unordered_map<std::int32_t, std::int32_t> new_label;  // old label -> new label, 0 = dropped
  for (const analysis::LabelRegion& r : regions) {
    std::int32_t assigned = 0;
    if (r.pixels < min_area) {
      ++table.dropped_small;
    } else if (drop_border && r.touches_border) {
      ++table.dropped_border;
    } else {
      Grain g;
      g.label = static_cast<std::int32_t>(table.grains.size()) + 1;
      g.pixels = r.pixels;
      g.shape = r.shape;
      g.centroid_col = r.centroid_col;
      g.centroid_row = r.centroid_row;
      g.bbox = r.bbox;
      g.touches_border = r.touches_border;
      table.grains.push_back(g);
      assigned = g.label;
    }
    new_label.emplace(r.label, assigned);
  }
  table.labels = cv::Mat::zeros(raw_labels.size(), CV_32S);
  table.dropped = cv::Mat::zeros(raw_labels.size(), CV_8U);
  cv::Mat grey64;
  grey.convertTo(grey64, CV_64F);
  std::vector<double> grey_sum(table.grains.size() + 1, 0.0);
  for (int r = 0; r < raw_labels.rows; ++r) {
    for (int c = 0; c < raw_labels.cols; ++c) {
      const std::int32_t old = raw_labels.at<std::int32_t>(r, c);
      if (old <= 0) continue;
      const std::int32_t l = new_label.at(old);
      if (l == 0) {
        table.dropped.at<unsigned char>(r, c) = 255;
        continue;
      }
      table.labels.at<std::int32_t>(r, c) = l;
      grey_sum[static_cast<std::size_t>(l)] += grey64.at<double>(r, c);
    }
  }
  for (Grain& g : table.grains) {
    g.mean_grey = grey_sum[static_cast<std::size_t>(g.label)] / static_cast<double>(g.pixels);
    g.phase = phase_of(g.mean_grey, phase_bands);
  }
  return table;
}

}  // namespace fragmpm::pipeline
