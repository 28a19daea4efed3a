#include "fragmpm/pipeline/segment_watershed.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <queue>
#include <unordered_map>
#include <utility>
#include <vector>

namespace fragmpm::pipeline {

namespace {

constexpr int kDr[4] = {-1, 1, 0, 0};
constexpr int kDc[4] = {0, 0, -1, 1};

struct UnionFind {
  std::vector<int> parent;
  explicit UnionFind(int n) : parent(static_cast<std::size_t>(n)) {
    std::iota(parent.begin(), parent.end(), 0);
  }
  int find(int a) {
    while (parent[static_cast<std::size_t>(a)] != a) {
      parent[static_cast<std::size_t>(a)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(a)])];
      a = parent[static_cast<std::size_t>(a)];
    }
    return a;
  }
};

}  // namespace

int compact_labels(cv::Mat& labels) {
  std::unordered_map<std::int32_t, std::int32_t> map;
  std::int32_t next = 0;
  for (int r = 0; r < labels.rows; ++r) {
    auto* row = labels.ptr<std::int32_t>(r);
    for (int c = 0; c < labels.cols; ++c) {
      if (row[c] <= 0) {
        row[c] = 0;
        continue;
      }
      auto [it, inserted] = map.try_emplace(row[c], next + 1);
      if (inserted) ++next;
      row[c] = it->second;
    }
  }
  return next;
}

cv::Mat connected_labels(const cv::Mat& mask) {
  cv::Mat labels;
  cv::connectedComponents(mask != 0, labels, 4, CV_32S);
  compact_labels(labels);  // OpenCV's numbering is already raster order; this makes it a guarantee
  return labels;
}

cv::Mat flood_labels(const cv::Mat& seeds, const cv::Mat& allowed, const cv::Mat& height) {
  const int rows = seeds.rows, cols = seeds.cols;
  cv::Mat labels = seeds.clone();
  const bool by_height = !height.empty();
  struct Entry {
    float priority;
    std::uint64_t
        order;  // FIFO among equal priorities keeps the flood deterministic and breadth-first
    int index;
  };
  auto lower = [](const Entry& a, const Entry& b) {
    if (a.priority != b.priority) return a.priority < b.priority;
    return a.order > b.order;
  };
  std::priority_queue<Entry, std::vector<Entry>, decltype(lower)> queue(lower);
  std::uint64_t order = 0;
  auto priority = [&](int r, int c) { return by_height ? height.at<float>(r, c) : 0.0f; };
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (labels.at<std::int32_t>(r, c) > 0) queue.push({priority(r, c), order++, r * cols + c});
  while (!queue.empty()) {
    const Entry e = queue.top();
    queue.pop();
    const int r = e.index / cols, c = e.index % cols;
    const std::int32_t l = labels.at<std::int32_t>(r, c);
    for (int k = 0; k < 4; ++k) {
      const int rr = r + kDr[k], cc = c + kDc[k];
      if (rr < 0 || cc < 0 || rr >= rows || cc >= cols) continue;
      if (!allowed.at<unsigned char>(rr, cc) || labels.at<std::int32_t>(rr, cc) != 0) continue;
      labels.at<std::int32_t>(rr, cc) = l;
      queue.push({priority(rr, cc), order++, rr * cols + cc});
    }
  }
  return labels;
}

cv::Mat split_touching_grains(const cv::Mat& mask, const SplitOptions& options) {
  cv::Mat fg = mask != 0;
  if (!options.enabled) return connected_labels(fg);

  cv::Mat dist;
  cv::distanceTransform(fg, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);

  // Markers: plateaus of pixels that are the maximum of the distance map within the spacing radius.
  const int radius = std::max(1, static_cast<int>(std::lround(options.marker_spacing)));
  cv::Mat dilated;
  cv::dilate(
      dist, dilated,
      cv::getStructuringElement(cv::MORPH_ELLIPSE, cv::Size(2 * radius + 1, 2 * radius + 1)));
  cv::Mat peaks = (dist >= dilated) & fg;
  cv::Mat seeds;
  cv::connectedComponents(peaks, seeds, 8, CV_32S);

  cv::Mat labels = flood_labels(seeds, fg, dist);
  // A grain whose maximum is outshone by a bigger neighbour within the radius got no marker: it
  // keeps its own label.
  cv::Mat leftover = fg & (labels == 0);
  if (cv::countNonZero(leftover) > 0) {
    double max_label = 0.0;
    cv::minMaxLoc(labels, nullptr, &max_label);
    cv::Mat extra = connected_labels(leftover);
    for (int r = 0; r < labels.rows; ++r)
      for (int c = 0; c < labels.cols; ++c)
        if (const std::int32_t e = extra.at<std::int32_t>(r, c); e > 0)
          labels.at<std::int32_t>(r, c) = static_cast<std::int32_t>(max_label) + e;
  }
  const int n = compact_labels(labels);

  // Neck criterion: peak = inscribed radius of each piece; saddle = highest distance value at
  // which two pieces meet (min of the two pixels across their shared boundary).
  std::vector<float> peak(static_cast<std::size_t>(n) + 1, 0.0f);
  std::unordered_map<std::uint64_t, float> saddle;
  auto key = [](std::int32_t a, std::int32_t b) {
    if (a > b) std::swap(a, b);
    return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
  };
  for (int r = 0; r < labels.rows; ++r) {
    for (int c = 0; c < labels.cols; ++c) {
      const std::int32_t a = labels.at<std::int32_t>(r, c);
      if (a == 0) continue;
      const float da = dist.at<float>(r, c);
      peak[static_cast<std::size_t>(a)] = std::max(peak[static_cast<std::size_t>(a)], da);
      for (const auto& [dr, dc] : {std::pair{1, 0}, std::pair{0, 1}}) {  // each pixel pair once
        const int rr = r + dr, cc = c + dc;
        if (rr >= labels.rows || cc >= labels.cols) continue;
        const std::int32_t b = labels.at<std::int32_t>(rr, cc);
        if (b == 0 || b == a) continue;
        const float s = std::min(da, dist.at<float>(rr, cc));
        auto [it, inserted] = saddle.try_emplace(key(a, b), s);
        if (!inserted) it->second = std::max(it->second, s);
      }
    }
  }
  struct Edge {
    std::int32_t a, b;
    float s;
  };
  std::vector<Edge> edges;
  edges.reserve(saddle.size());
  for (const auto& [k, s] : saddle)
    edges.push_back(
        {static_cast<std::int32_t>(k >> 32), static_cast<std::int32_t>(k & 0xffffffffu), s});
  // Highest necks first, so every edge examined is the highest remaining link between two groups
  // (as in a component tree); ties broken by labels for determinism.
  std::sort(edges.begin(), edges.end(), [](const Edge& x, const Edge& y) {
    if (x.s != y.s) return x.s > y.s;
    if (x.a != y.a) return x.a < y.a;
    return x.b < y.b;
  });
  UnionFind uf(n + 1);
  for (const Edge& e : edges) {
    const int ra = uf.find(e.a), rb = uf.find(e.b);
    if (ra == rb) continue;
    const float pa = peak[static_cast<std::size_t>(ra)], pb = peak[static_cast<std::size_t>(rb)];
    if (e.s >= options.neck_ratio * std::min(pa, pb)) {
      const int root = std::min(ra, rb), child = std::max(ra, rb);
      uf.parent[static_cast<std::size_t>(child)] = root;
      peak[static_cast<std::size_t>(root)] = std::max(pa, pb);
    }
  }
  for (int r = 0; r < labels.rows; ++r) {
    auto* row = labels.ptr<std::int32_t>(r);
    for (int c = 0; c < labels.cols; ++c)
      if (row[c] > 0) row[c] = uf.find(row[c]);
  }
  compact_labels(labels);
  return labels;
}

void fill_enclosed_holes(cv::Mat& labels) {
  cv::Mat background = labels == 0;
  cv::Mat comp;
  const int n = cv::connectedComponents(background, comp, 4, CV_32S);
  // Per background component: the single neighbouring grain, −1 when it reaches the border or
  // touches two grains, 0 while unknown.
  std::vector<std::int32_t> owner(static_cast<std::size_t>(n), 0);
  const int rows = labels.rows, cols = labels.cols;
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const int k = comp.at<int>(r, c);
      if (k == 0) continue;
      std::int32_t& o = owner[static_cast<std::size_t>(k)];
      if (o < 0) continue;
      if (r == 0 || c == 0 || r == rows - 1 || c == cols - 1) {
        o = -1;
        continue;
      }
      for (int d = 0; d < 4; ++d) {
        const std::int32_t l = labels.at<std::int32_t>(r + kDr[d], c + kDc[d]);
        if (l == 0) continue;
        if (o == 0)
          o = l;
        else if (o != l)
          o = -1;
      }
    }
  }
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c)
      if (const int k = comp.at<int>(r, c); k > 0 && owner[static_cast<std::size_t>(k)] > 0)
        labels.at<std::int32_t>(r, c) = owner[static_cast<std::size_t>(k)];
}

std::int64_t remove_small_grains(cv::Mat& labels, std::int64_t min_area, cv::Mat& removed) {
  if (removed.empty()) removed = cv::Mat::zeros(labels.size(), CV_8U);
  double max_label = 0.0;
  cv::minMaxLoc(labels, nullptr, &max_label);
  std::vector<std::int64_t> count(static_cast<std::size_t>(max_label) + 1, 0);
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c)
      if (const std::int32_t l = labels.at<std::int32_t>(r, c); l > 0)
        ++count[static_cast<std::size_t>(l)];
  std::int64_t dropped = 0;
  for (std::size_t l = 1; l < count.size(); ++l) dropped += count[l] > 0 && count[l] < min_area;
  for (int r = 0; r < labels.rows; ++r)
    for (int c = 0; c < labels.cols; ++c) {
      std::int32_t& l = labels.at<std::int32_t>(r, c);
      if (l > 0 && count[static_cast<std::size_t>(l)] < min_area) {
        l = 0;
        removed.at<unsigned char>(r, c) = 255;
      }
    }
  return dropped;
}

void grow_labels(cv::Mat& labels, double radius) {
  if (!(radius > 0.0)) return;
  cv::Mat background = labels == 0, dist;
  cv::distanceTransform(background, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
  const cv::Mat allowed = (labels > 0) | (dist <= radius);
  labels = flood_labels(labels, allowed);
}

}  // namespace fragmpm::pipeline
