#pragma once
// The parts of the phase-field stage (phase_field_stage.cpp), in the order it calls them, and what
// they share: which slot of a node holds a body's field, and where a node offset sits in a row of
// the band. Each part is defined in the file of its name in this folder.
#include <cstdint>

#include "step/phase_field_state.hpp"
#include "step/step_state.hpp"

namespace fragmpm::mpm {

/// Particle p has the phase-field law.
template <int D>
inline bool has_phase_field(const StepState<D>& state, std::int64_t p) {
  return state.material_damages[static_cast<std::size_t>(state.problem.particles.material[p])] ==
         material_phase_field;
}

/// The field of a particle of `body` in this step (0 when the step's bodies share one field).
template <int D>
inline std::int32_t field_of_body(const PhaseFieldState<D>& pf, std::int32_t body) {
  return pf.shared_fields ? std::int32_t{0} : body;
}

/// The slot of node i that holds `field` (a body, or 0 when the bodies share one field).
template <int D>
inline int slot_of(const PhaseFieldState<D>& pf, std::size_t node, std::int32_t field) {
  constexpr int K = PhaseFieldState<D>::slots;
  const std::int32_t* fields = pf.node_body.data() + node * K;
  for (int s = 0; s < K - 1; ++s)
    if (fields[s] == field) return s;
  return K - 1;
}

/// Index of node offset o ∈ [−reach, reach]^D in a row of the band.
template <int D>
inline int band_index(const IVec<D>& offset, int reach) {
  int index = 0, stride = 1;
  for (int k = 0; k < D; ++k) {
    index += static_cast<int>(offset[k] + reach) * stride;
    stride *= 2 * reach + 1;
  }
  return index;
}

/// The fourth-order anisotropic term is on for this material (only compiled where it can be: the
/// B-spline in 2D).
template <int D, ShapeFunctionKind Kind>
inline bool has_fourth_order(const PhaseFieldState<D>& pf, std::size_t material) {
  if constexpr (D == 2 && Kind == ShapeFunctionKind::bspline2)
    return pf.anisotropic[material] != 0;
  else
    return (void)pf, (void)material, false;
}

/// Steps 1-2: the fields that reach each node and one unknown per node and field, in node order
/// (node_body, node_unknown, unknown_node, unknown_body, shared_fields). (phase_field_unknowns.cpp)
template <int D, ShapeFunctionKind Kind>
void number_phase_field_unknowns(StepState<D>& state);
/// Steps 3-4: [KT19] eq. (57) and (52) by particle quadrature, in compressed rows (outer, inner,
/// values, rhs), the particles' projected c as a guess, and the unknowns of cracked particles for
/// the crack block. (phase_field_assembly.cpp)
template <int D, ShapeFunctionKind Kind>
void assemble_phase_field_system(StepState<D>& state);
/// Step 5: the solve, by conjugate gradients or directly, from the warm start; updates the warm
/// start for the next step. (phase_field_solve.cpp)
template <int D>
void solve_phase_field_system(StepState<D>& state);
/// Step 6: d and the crack energy at the particles from the solution.
/// (phase_field_interpolation.cpp)
template <int D, ShapeFunctionKind Kind>
void interpolate_phase_field(StepState<D>& state);

}  // namespace fragmpm::mpm
