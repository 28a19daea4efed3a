// The grid update of the explicit step: v_i = p_i / m_i, then v_i + Δt f_i / m_i, the explicit form
// of m_i a_i = f_i ([XLS21] eq. (46)).
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
void update_grid_velocities(StepState<D>& state, double dt) {
  const std::int64_t nodes = static_cast<std::int64_t>(state.node_count());
  const double negligible = state.negligible_mass;
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
        velocity[i] = lumped[i] + dt * force[i] / mass[i];
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
