#pragma once
// Measures of the convex hull of a planar point set (CGAL convex hull, then rotating calipers):
// hull area and perimeter (for solidity = area / hull area) and the Feret (caliper) diameters.
#include <Eigen/Core>
#include <cstddef>
#include <span>

namespace fragmpm::analysis {

struct ConvexMeasures {
  double hull_area = 0.0;       ///< [u²]
  double hull_perimeter = 0.0;  ///< [u]
  double feret_max = 0.0;       ///< largest caliper distance = diameter of the point set [u]
  double feret_min = 0.0;       ///< smallest caliper distance = minimum width [u]
  double feret_max_angle = 0.0;  ///< direction of the maximum Feret segment from +x, in (−π/2, π/2]
  std::size_t hull_vertices = 0;
};

/// Convex hull of `points` (CGAL::convex_hull_2, exact predicates) and its calipers. The minimum
/// width of a convex polygon is attained with one caliper flush with an edge, so it is the
/// smallest, over the hull edges, of the largest distance of a vertex from the edge's line; the
/// maximum is the largest distance between antipodal vertices. Both come from one rotating-calipers
/// sweep, O(h). Fewer than 3 non-collinear points give a zero area and zero minimum width.
ConvexMeasures convex_hull_measures(std::span<const Eigen::Vector2d> points);

}  // namespace fragmpm::analysis
