#pragma once
// What a phase-field run carries from one nodal solve to the next ([KT19] Alg. 1 solves the
// phase-field system once a step): the last solution c = 1 − d per grid node and field, which
// starts the next conjugate-gradient solve, and whether the next solve is direct. A checkpoint
// stores it, so a restarted run repeats the uninterrupted one bit for bit.
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

template <int D>
struct PhaseFieldWarmStart {
  std::vector<IVec<D>> node;        ///< global grid node of each unknown
  std::vector<std::int32_t> field;  ///< its field (body, or 0 when the bodies shared one)
  std::vector<double> solution;     ///< c = 1 − d at the node
  bool direct = false;              ///< the next solve factorises the system (else Jacobi CG)

  bool empty() const { return solution.empty(); }
};

}  // namespace fragmpm::mpm
