#pragma once
// The active nodes on or behind a plane, without scanning the whole grid: along the axis closest to
// the plane normal only the index range that can pass the plane test is visited, so a wall costs
// the slab of nodes near it, not the active region.
#include <algorithm>
#include <cmath>
#include <cstdint>

#include "fragmpm/mpm/grid_index.hpp"

namespace fragmpm::mpm {

/// Calls visit(i, x_i) for every active node i with (x_i − point)·normal ≤ offset, in ascending
/// linear order (the order a full scan would give, so sums over the nodes do not change).
template <int D, class Visit>
void for_each_node_behind_plane(const GridIndex<D>& grid, const Vec<D>& point, const Vec<D>& normal,
                                double offset, Visit&& visit) {
  int axis = 0;
  for (int k = 1; k < D; ++k)
    if (std::abs(normal[k]) > std::abs(normal[axis])) axis = k;
  IVec<D> first = IVec<D>::Zero(), extent = grid.extent;
  if (normal[axis] != 0.0) {
    // Most permissive bound over the box of the other axes: (x_a − p_a) n_a ≤ offset − min Σ_{k≠a}.
    double slack = offset;
    for (int k = 0; k < D; ++k) {
      if (k == axis) continue;
      const double lo =
          grid.origin[k] + grid.cell_size * static_cast<double>(grid.lower[k]) - point[k];
      const double hi = lo + grid.cell_size * static_cast<double>(grid.extent[k] - 1);
      slack -= std::min(lo * normal[k], hi * normal[k]);
    }
    const double limit = point[axis] + slack / normal[axis];  // x_a ≤ limit (n_a > 0) or ≥ limit
    const double index = (limit - grid.origin[axis]) * grid.inverse_cell_size -
                         static_cast<double>(grid.lower[axis]);
    // One node of margin each way against rounding; the exact test below decides.
    std::int64_t lo = 0, hi = grid.extent[axis] - 1;
    if (normal[axis] > 0.0)
      hi = std::min(hi, static_cast<std::int64_t>(std::floor(index)) + 1);
    else
      lo = std::max(lo, static_cast<std::int64_t>(std::ceil(index)) - 1);
    if (hi < lo) return;
    first[axis] = lo;
    extent[axis] = hi - lo + 1;
  }
  std::int64_t total = 1;
  for (int k = 0; k < D; ++k) total *= extent[k];
  for (std::int64_t sub = 0; sub < total; ++sub) {
    std::int64_t rest = sub, linear = 0, stride = 1;
    IVec<D> node;
    for (int k = 0; k < D; ++k) {
      const std::int64_t local = first[k] + rest % extent[k];
      rest /= extent[k];
      linear += local * stride;
      stride *= grid.extent[k];
      node[k] = grid.lower[k] + local;
    }
    const Vec<D> x = grid.position(node);
    if ((x - point).dot(normal) > offset) continue;
    visit(linear, x);
  }
}

}  // namespace fragmpm::mpm
