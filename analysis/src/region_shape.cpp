#include "fragmpm/analysis/region_shape.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace fragmpm::analysis {

ShapeCell pixel_cell(double x, double y, double side) {
  const double own = side * side / 12.0;  // variance of a uniform distribution over [0, side]
  return {x, y, side * side, own, own, 0.0};
}

ShapeCell parallelogram_cell(double x, double y, double r1x, double r1y, double r2x, double r2y) {
  // Points c + s r1 + t r2 with s, t uniform on [−½, ½]: Cov = (r1 r1ᵀ + r2 r2ᵀ)/12.
  return {x,
          y,
          std::abs(r1x * r2y - r1y * r2x),
          (r1x * r1x + r2x * r2x) / 12.0,
          (r1y * r1y + r2y * r2y) / 12.0,
          (r1x * r1y + r2x * r2y) / 12.0};
}

void RegionMoments::add(const ShapeCell& c) {
  if (cells == 0) {
    x0 = c.x;
    y0 = c.y;
  }
  const double dx = c.x - x0;
  const double dy = c.y - y0;
  area += c.area;
  sx += c.area * dx;
  sy += c.area * dy;
  sxx += c.area * (dx * dx + c.cxx);
  syy += c.area * (dy * dy + c.cyy);
  sxy += c.area * (dx * dy + c.cxy);
  ++cells;
}

RegionShape region_shape(const RegionMoments& m, double perimeter) {
  RegionShape s;
  s.perimeter = perimeter;
  if (!(m.area > 0.0)) return s;
  const double A = m.area;
  const double mx = m.sx / A;
  const double my = m.sy / A;
  s.area = A;
  s.equivalent_diameter = std::sqrt(4.0 * A / std::numbers::pi);
  s.centroid_x = m.x0 + mx;
  s.centroid_y = m.y0 + my;

  // Central second moments per unit area (covariance of the region's area distribution).
  const double cxx = std::max(0.0, m.sxx / A - mx * mx);
  const double cyy = std::max(0.0, m.syy / A - my * my);
  const double cxy = m.sxy / A - mx * my;
  const double half_trace = 0.5 * (cxx + cyy);
  const double radius = std::hypot(0.5 * (cxx - cyy), cxy);
  const double l1 = half_trace + radius;
  const double l2 = std::max(0.0, half_trace - radius);
  s.orientation = 0.5 * std::atan2(2.0 * cxy, cxx - cyy);
  if (s.orientation <= -std::numbers::pi / 2) s.orientation += std::numbers::pi;

  // An ellipse of semi-axes p, q has variances p²/4, q²/4 along its axes, so the moment-equivalent
  // ellipse has full axes 4√λ1, 4√λ2; ImageJ rescales it to the region's area (π a b / 4 = A),
  // which keeps the ratio b/a = √(λ2/λ1).
  if (l1 <= 0.0) {  // a point-like region without own extent: call it round
    s.major_axis = s.minor_axis = s.equivalent_diameter;
    s.roundness = s.aspect_ratio = 1.0;
    return s;
  }
  const double ratio = std::sqrt(l2 / l1);  // b/a
  if (ratio > 0.0) {
    s.major_axis = std::sqrt(4.0 * A / (std::numbers::pi * ratio));
    s.minor_axis = s.major_axis * ratio;
    s.aspect_ratio = 1.0 / ratio;
  } else {  // a line of cells without width: keep the second-moment length, no rescaling possible
    s.major_axis = 4.0 * std::sqrt(l1);
    s.minor_axis = 0.0;
    s.aspect_ratio = std::numeric_limits<double>::infinity();
  }
  s.roundness = ratio;  // 4A/(π a²) with π a b/4 = A
  return s;
}

RegionShape region_shape(std::span<const ShapeCell> cells, double perimeter) {
  RegionMoments m;
  for (const ShapeCell& c : cells) m.add(c);
  return region_shape(m, perimeter);
}

double crofton_perimeter(std::int64_t n0, std::int64_t n90, std::int64_t n45, std::int64_t n135,
                         double side) {
  // Cauchy–Crofton: L = ½ ∫₀^π ∫ n(θ, p) dp dθ. Four directions share π/4 each; axis-parallel lines
  // through pixel centres are spaced `side` apart, diagonal ones side/√2.
  const double axis = static_cast<double>(n0 + n90);
  const double diagonal = static_cast<double>(n45 + n135) / std::numbers::sqrt2;
  return std::numbers::pi / 8.0 * (axis + diagonal) * side;
}

std::vector<LabelRegion> label_region_shapes(const cv::Mat& labels, double pixel_size) {
  if (labels.type() != CV_32SC1)
    throw std::invalid_argument("label_region_shapes: label image must be CV_32SC1");
  if (!(pixel_size > 0.0))
    throw std::invalid_argument("label_region_shapes: pixel size must be positive, got " +
                                std::to_string(pixel_size));
  const int rows = labels.rows;
  const int cols = labels.cols;
  std::int32_t max_label = 0;
  for (int r = 0; r < rows; ++r) {
    const auto* row = labels.ptr<std::int32_t>(r);
    for (int c = 0; c < cols; ++c) max_label = std::max(max_label, row[c]);
  }
  struct Acc {
    RegionMoments m;
    std::int64_t pixels = 0, n0 = 0, n90 = 0, n45 = 0, n135 = 0;
    double sum_col = 0.0, sum_row = 0.0;
    int cmin = 0, cmax = -1, rmin = 0, rmax = -1;
  };
  // Accumulators indexed by label; a sparse label set (huge label values) is compacted first so the
  // memory stays proportional to the number of regions.
  std::vector<std::int32_t> slot_label;  // slot -> label
  std::vector<std::int32_t> dense_slot;  // label -> slot, when labels are dense
  const std::int64_t total = static_cast<std::int64_t>(rows) * cols;
  const bool dense = max_label <= 4 * total + 16;
  if (dense) {
    dense_slot.assign(static_cast<std::size_t>(max_label) + 1, -1);
  } else {
    for (int r = 0; r < rows; ++r) {
      const auto* row = labels.ptr<std::int32_t>(r);
      for (int c = 0; c < cols; ++c)
        if (row[c] > 0) slot_label.push_back(row[c]);
    }
    std::sort(slot_label.begin(), slot_label.end());
    slot_label.erase(std::unique(slot_label.begin(), slot_label.end()), slot_label.end());
  }
  auto slot_of = [&](std::int32_t l) -> std::size_t {
    if (dense) {
      std::int32_t& s = dense_slot[static_cast<std::size_t>(l)];
      if (s < 0) {
        s = static_cast<std::int32_t>(slot_label.size());
        slot_label.push_back(l);
      }
      return static_cast<std::size_t>(s);
    }
    return static_cast<std::size_t>(std::lower_bound(slot_label.begin(), slot_label.end(), l) -
                                    slot_label.begin());
  };
  std::vector<Acc> acc(dense ? 0 : slot_label.size());
  auto at = [&](int r, int c) -> std::int32_t {
    return (r < 0 || c < 0 || r >= rows || c >= cols) ? 0 : labels.at<std::int32_t>(r, c);
  };
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      const std::int32_t l = labels.at<std::int32_t>(r, c);
      if (l <= 0) continue;
      const std::size_t slot = slot_of(l);
      if (slot >= acc.size()) acc.resize(slot + 1);
      Acc& a = acc[slot];
      if (a.pixels == 0) {
        a.cmin = a.cmax = c;
        a.rmin = a.rmax = r;
      }
      a.cmin = std::min(a.cmin, c);
      a.cmax = std::max(a.cmax, c);
      a.rmin = std::min(a.rmin, r);
      a.rmax = std::max(a.rmax, r);
      ++a.pixels;
      a.sum_col += c + 0.5;
      a.sum_row += r + 0.5;
      a.m.add(pixel_cell((c + 0.5) * pixel_size, (rows - r - 0.5) * pixel_size, pixel_size));
      // Crossings of the centre-to-centre lines leaving this pixel, one direction pair at a time.
      a.n0 += (at(r, c + 1) != l) + (at(r, c - 1) != l);
      a.n90 += (at(r + 1, c) != l) + (at(r - 1, c) != l);
      a.n45 += (at(r - 1, c + 1) != l) + (at(r + 1, c - 1) != l);
      a.n135 += (at(r - 1, c - 1) != l) + (at(r + 1, c + 1) != l);
    }
  }
  std::vector<std::size_t> order(acc.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return slot_label[a] < slot_label[b]; });
  std::vector<LabelRegion> out;
  out.reserve(acc.size());
  for (const std::size_t k : order) {
    const Acc& a = acc[k];
    LabelRegion region;
    region.label = slot_label[k];
    region.pixels = a.pixels;
    region.shape = region_shape(a.m, crofton_perimeter(a.n0, a.n90, a.n45, a.n135, pixel_size));
    region.bbox = cv::Rect(a.cmin, a.rmin, a.cmax - a.cmin + 1, a.rmax - a.rmin + 1);
    region.centroid_col = a.sum_col / static_cast<double>(a.pixels);
    region.centroid_row = a.sum_row / static_cast<double>(a.pixels);
    region.touches_border = a.cmin == 0 || a.rmin == 0 || a.cmax == cols - 1 || a.rmax == rows - 1;
    out.push_back(region);
  }
  return out;
}

}  // namespace fragmpm::analysis
