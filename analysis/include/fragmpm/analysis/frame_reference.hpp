#pragma once
// The reference configuration of the particles a frame holds. A run with `[grid] outside =
// "remove"` loses the particles that leave the domain, so a later frame holds fewer particles than
// the first one; each particle's `id` (its index at step 0) finds its row in the first frame.
#include <cstddef>

#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

struct FrameReference {
  mpm::Particles<2>
      particles;               ///< rows of the first frame, one per particle of the frame, in order
  std::size_t departed = 0;    ///< particles of the first frame that are not in this one
  double departed_mass = 0.0;  ///< their mass [kg/m], from the first frame
};

/// Picks the rows of `first` (the run's first frame) whose id is in `current`, in the order of
/// `current`. Throws std::invalid_argument when an id of `current` is not in `first` or appears
/// twice, or when `current` has more particles than `first`.
FrameReference frame_reference(const mpm::Particles<2>& first, const mpm::Particles<2>& current);

}  // namespace fragmpm::analysis
