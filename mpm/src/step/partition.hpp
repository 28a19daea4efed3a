#pragma once
// Field decisions of damage-field-gradient partitioning shared by the partition, contact and
// thermal stages ([HH17] Alg. 2-3).
#include <algorithm>
#include <cstdint>

#include "step/step_state.hpp"

namespace fragmpm::mpm {

/// Whether the two fields of node i (both holding mass) may separate: [HH17] §2.3, Alg. 3;
/// [XLS21] eq. (70)-(71) on d̂ = max(s, d). Valid after the scatter of a partitioned step.
template <int D>
inline bool node_separable(const StepState<D>& state, std::size_t i) {
  if (state.plan.by_bodies) return true;
  const ContactSums<D>& sums = state.contact;
  const auto& mass = state.nodes.mass;
  return sums.dhat_max[i] >= state.problem.contact.critical_damage &&
         std::min(sums.dhat[0][i] / mass[0][i], sums.dhat[1][i] / mass[1][i]) >
             state.problem.contact.minimum_damage;
}

}  // namespace fragmpm::mpm
