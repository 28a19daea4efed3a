// The kinetic energy the grid-to-particle transfer takes out of a step, booked as
// transfer_dissipation.
//
// With l = p/m the lumped velocity of a field at a node, v its velocity after contact and walls and
// a = v − (its lumped velocity after contact) the FLIP increment the particles receive, the
// particles' kinetic energy after G2P follows from the nodes up to one gap:
//   FLIP: Σ_p ½ m_p |v_p + a_p|² = K_old + Σ_i m l·a + Σ_p ½ m_p |a_p|², a_p = Σ_i S̄_ip a_i,
//         because Σ_p m_p v_p·a_p = Σ_i a_i·Σ_p S̄_ip m_p v_p = Σ_i m l·a exactly. Jensen's
//         inequality on the weights S̄_ip (a partition of unity, per field) gives Σ_p ½ m_p|a_p|² ≤
//         Σ_i ½ m|a|².
//   PIC:  Σ_p ½ m_p |Σ_i S̄_ip v_i|² ≤ Σ_i ½ m |v|², and the grid started from Σ_i ½ m |l|² ≤ K_old.
// The contact and explicit-step identities (contact_energy.cpp) hold for the nodes' energy
//     K_old + Σ_i [(1 − ζ)(m l·a + ½ m|a|²) + ζ ½ m (|v|² − |l|²)],
// ζ the PIC fraction (1 for APIC). What the particles end with is smaller by the transfer's
// smoothing of the nodal increments (FLIP) and the projection of the particle velocities onto the
// grid (PIC); the difference is exact, ≥ 0 for the FLIP/PIC blend by convexity, and is booked here.
// For APIC, K includes the affine part ½ m tr(C Q Cᵀ) on both sides ([JSS15] §5).
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
double nodal_kinetic_energy_change(const StepState<D>& state) {
  const NodeFields<D>& N = state.nodes;
  const double pic =
      state.problem.time.transfer == Transfer::apic ? 1.0 : state.problem.time.pic_fraction;
  const double negligible = state.negligible_mass;
  const std::int64_t nodes = static_cast<std::int64_t>(state.node_count());
  double change = 0.0;
  for (int f = 0; f < state.fields(); ++f) {
    const auto& mass = N.mass[f];
    const auto& momentum = N.momentum[f];
    const auto& velocity = N.velocity[f];
    const auto& velocity_lumped = N.velocity_lumped[f];
    // Each field's sum starts from zero: OpenMP adds the threads' partial sums to the shared value
    // in the order the threads finish, which is exact for two partial sums and zero but not when
    // the first field's total is already there (a restart would then differ in the last bit).
    double field_change = 0.0;
#pragma omp parallel for reduction(+ : field_change) schedule(static)
    for (std::int64_t i = 0; i < nodes; ++i) {
      const double m = mass[i];
      if (!(m > negligible)) continue;
      const Vec<D> lumped = momentum[i] / m;
      const Vec<D> received = velocity[i] - velocity_lumped[i];
      const double flip = m * (lumped.dot(received) + 0.5 * received.squaredNorm());
      const double projected = 0.5 * m * (velocity[i].squaredNorm() - lumped.squaredNorm());
      field_change += (1.0 - pic) * flip + pic * projected;
    }
    change += field_change;
  }
  return change;
}

template double nodal_kinetic_energy_change<2>(const StepState<2>&);
template double nodal_kinetic_energy_change<3>(const StepState<3>&);

}  // namespace fragmpm::mpm
