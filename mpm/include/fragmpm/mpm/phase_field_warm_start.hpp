#pragma once
// What a phase-field run carries from one nodal solve to the next ([KT19] Alg. 1 solves the
// phase-field system once a step): the last solution c = 1 − d per grid node and field, which
// starts the next conjugate-gradient solve, and how many of the next solves are direct. A
// checkpoint stores it, so a restarted run repeats the uninterrupted one bit for bit.
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Conjugate-gradient iterations at which a phase-field solve stops and factorises the whole
/// system instead (why: step/phase_field_state.hpp).
inline constexpr int phase_field_iteration_limit = 300;
/// Direct solves after a conjugate-gradient solve stops at its iteration limit, before the next
/// attempt (the first time, and at most, doubling while the attempts keep failing). An attempt
/// that fails costs the limit's 300 iterations, on the colliding rings' 12 000 unknowns about
/// two factorisations of the whole system (a profile of that run puts 0.35 ms of CPU time in an
/// iteration; a factorisation takes about 45 ms): spread over 64 or more direct solves that is a
/// few per cent, while a single hard solve no longer condemns the rest of the run to
/// factorisations (step/phase_field_state.hpp).
inline constexpr std::int32_t first_direct_run = 64;
inline constexpr std::int32_t longest_direct_run = 4096;

template <int D>
struct PhaseFieldWarmStart {
  std::vector<IVec<D>> node;        ///< global grid node of each unknown
  std::vector<std::int32_t> field;  ///< its field (body, or 0 when the bodies shared one)
  std::vector<double> solution;     ///< c = 1 − d at the node
  /// Solves left that factorise the whole system before conjugate gradients are tried again
  /// (0: the next solve iterates), and the length of the run of direct solves they belong to
  /// (0: the last conjugate-gradient solve converged within its iteration limit).
  std::int32_t direct_solves_left = 0;
  std::int32_t direct_run = 0;

  bool empty() const { return solution.empty(); }
};

}  // namespace fragmpm::mpm
