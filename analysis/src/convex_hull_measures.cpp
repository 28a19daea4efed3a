#include "fragmpm/analysis/convex_hull_measures.hpp"

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/convex_hull_2.h>

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>
#include <numbers>
#include <vector>

namespace fragmpm::analysis {

namespace {
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_2;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

double direction_angle(const Eigen::Vector2d& d) {
  double a = std::atan2(d.y(), d.x());
  if (a > std::numbers::pi / 2) a -= std::numbers::pi;
  if (a <= -std::numbers::pi / 2) a += std::numbers::pi;
  return a;
}
}  // namespace

ConvexMeasures convex_hull_measures(std::span<const Eigen::Vector2d> points) {
  ConvexMeasures m;
  if (points.empty()) return m;
  std::vector<Point> in;
  in.reserve(points.size());
  for (const auto& p : points) in.emplace_back(p.x(), p.y());
  std::vector<Point> out;
  CGAL::convex_hull_2(in.begin(), in.end(), std::back_inserter(out));  // counter-clockwise
  std::vector<Eigen::Vector2d> h;
  h.reserve(out.size());
  for (const Point& p : out) h.emplace_back(p.x(), p.y());
  const std::size_t n = h.size();
  m.hull_vertices = n;
  if (n == 1) return m;
  if (n == 2) {  // all points on one segment
    m.feret_max = (h[1] - h[0]).norm();
    m.feret_max_angle = direction_angle(h[1] - h[0]);
    m.hull_perimeter = 2.0 * m.feret_max;
    return m;
  }
  for (std::size_t i = 0; i < n; ++i) {
    const auto& a = h[i];
    const auto& b = h[(i + 1) % n];
    m.hull_area += 0.5 * cross(a, b);  // shoelace, positive for counter-clockwise
    m.hull_perimeter += (b - a).norm();
  }
  // Rotating calipers: for edge (i, i+1) advance j to the vertex farthest from the edge's line (the
  // distance is unimodal around a convex polygon); j only moves forward, so the sweep is O(n).
  double best_max2 = 0.0;
  Eigen::Vector2d best_pair = h[1] - h[0];
  double min_width = std::numeric_limits<double>::infinity();
  std::size_t j = 1;
  auto height = [&](std::size_t i, std::size_t k) {
    return cross(h[(i + 1) % n] - h[i], h[k % n] - h[i]);
  };
  for (std::size_t i = 0; i < n; ++i) {
    const std::size_t i1 = (i + 1) % n;
    if (j == i) j = i1;
    while (height(i, j + 1) > height(i, j)) j = (j + 1) % n;
    const double edge = (h[i1] - h[i]).norm();
    if (edge > 0.0) min_width = std::min(min_width, height(i, j) / edge);
    // (i, j) and (i+1, j) are antipodal pairs; the diameter is attained at one of them.
    for (const std::size_t a : {i, i1}) {
      const double d2 = (h[j % n] - h[a]).squaredNorm();
      if (d2 > best_max2) {
        best_max2 = d2;
        best_pair = h[j % n] - h[a];
      }
    }
  }
  m.feret_max = std::sqrt(best_max2);
  m.feret_max_angle = direction_angle(best_pair);
  m.feret_min = std::isfinite(min_width) ? min_width : 0.0;
  return m;
}

}  // namespace fragmpm::analysis
