// The grid update of the explicit step: v_i = p_i / m_i, then v_i + Δt f_i / m_i, the explicit form
// of m_i a_i = f_i ([XLS21] eq. (46)). With `[time] damping` α > 0 the nodal equation is
// m_i a_i = f_i − α m_i v_i, taken implicit in the damping term:
// v_i ← (v_i + Δt f_i / m_i) / (1 + α Δt), stable for every α Δt and exact for a rigid motion
// ((1 + αΔt)^(−n) per n steps, → exp(−α t)). Mass-proportional damping decays every underdamped
// mode at the same rate α/2, and a mode of frequency ω ≪ α at ω²/α: dynamic relaxation picks α near
// twice the lowest frequency of the structure. With α = 0 the factor is exactly 1 and the update
// is bit-identical to the undamped one.
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
void update_grid_velocities(StepState<D>& state, double dt) {
  const std::int64_t nodes = static_cast<std::int64_t>(state.node_count());
  const double negligible = state.negligible_mass;
  const double damping_factor = 1.0 / (1.0 + state.problem.time.damping * dt);
  for (int f = 0; f < state.fields(); ++f) {
    const auto& mass = state.nodes.mass[f];
    const auto& momentum = state.nodes.momentum[f];
    const auto& force = state.nodes.force[f];
    auto& lumped = state.nodes.velocity_lumped[f];
    auto& velocity = state.nodes.velocity[f];
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < nodes; ++i) {
      // Nodes lighter than the negligible mass carry no velocity: their mass comes from the far
      // tail of a shape function, and dividing by it would amplify round-off.
      if (mass[i] > negligible) {
        lumped[i] = momentum[i] / mass[i];
        velocity[i] = damping_factor * (lumped[i] + dt * force[i] / mass[i]);
      } else {
        lumped[i].setZero();
        velocity[i].setZero();
      }
    }
  }
}

template void update_grid_velocities<2>(StepState<2>&, double);
template void update_grid_velocities<3>(StepState<3>&, double);

}  // namespace fragmpm::mpm
