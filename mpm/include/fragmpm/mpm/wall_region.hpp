#pragma once
// The part of a rigid wall's plane that acts: everywhere, or only inside a box that moves with the
// wall (a finite platen, or the rigid blocks that drive the oscillating block of [NBS18] Fig. 6).
#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

template <int D>
struct WallRegion {
  bool bounded = false;
  Vec<D> min = Vec<D>::Zero();  ///< [m] at t = 0
  Vec<D> max = Vec<D>::Zero();  ///< [m] at t = 0

  /// Whether a node at `point` is inside the box after the wall has moved by `shift` [m].
  bool contains(const Vec<D>& point, const Vec<D>& shift, double tolerance) const {
    if (!bounded) return true;
    const Vec<D> local = point - shift;
    return (local.array() >= min.array() - tolerance).all() &&
           (local.array() <= max.array() + tolerance).all();
  }
};

}  // namespace fragmpm::mpm
