#pragma once
// Maps global node coordinates to the linear index of the active region (docs/design.md: the grid
// exists only over the bounding box of the particles plus padding, refreshed every step).
#include <cmath>
#include <cstdint>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

template <int D>
struct GridIndex {
  Vec<D> origin = Vec<D>::Zero();    ///< position of global node (0, …, 0) [m]
  double cell_size = 1.0;            ///< h [m]
  double inverse_cell_size = 1.0;    ///< 1/h [1/m]
  IVec<D> lower = IVec<D>::Zero();   ///< global index of the first active node
  IVec<D> extent = IVec<D>::Ones();  ///< active nodes per direction

  std::int64_t node_count() const {
    std::int64_t n = 1;
    for (int k = 0; k < D; ++k) n *= extent[k];
    return n;
  }
  /// Linear index of global node `node` (row-major, direction 0 fastest).
  std::int64_t linear(const IVec<D>& node) const {
    std::int64_t index = 0, stride = 1;
    for (int k = 0; k < D; ++k) {
      index += (node[k] - lower[k]) * stride;
      stride *= extent[k];
    }
    return index;
  }
  IVec<D> global(std::int64_t linear_index) const {
    IVec<D> node;
    for (int k = 0; k < D; ++k) {
      node[k] = lower[k] + linear_index % extent[k];
      linear_index /= extent[k];
    }
    return node;
  }
  Vec<D> position(const IVec<D>& node) const {
    return origin + cell_size * node.template cast<double>();
  }
};

}  // namespace fragmpm::mpm
