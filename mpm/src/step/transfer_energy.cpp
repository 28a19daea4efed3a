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
//
// The strain side of the gap (FLIP). With M the lumped mass (m_i per node and field) and
// C = S̄ M_p S̄ᵀ the consistent one, the particles' momenta after the step, projected back onto the
// grid, give the velocity λ + M⁻¹C a, but update-stress-last moves and strains the material with
// v = λ + a, i.e. Δt (a − M⁻¹C a) farther. A step that moved it with λ + M⁻¹C a (the modified
// update-stress-last, which projects the updated momenta again before the strain update) is a
// symplectic Euler step of H = ½ pᵀ M⁻¹ C M⁻¹ p + U with p = M c (c the nodal coefficients of the
// particles' velocity field), whose energy error is bounded and does not drift (for weights held
// fixed over the step). The extra motion costs the stored energy Δt f·(a − M⁻¹C a) per node. Where
// nothing changed the nodal velocity, a = b = Δt f/m and this is b·(M a − C a)_i = 2 G_i, G_i = ½
// a_i·(m_i a_i − (C a)_i), whose sum is the kinetic gap above: the transfer takes twice the kinetic
// gap, and the nodal identities of contact_energy.cpp see only the kinetic half, the other half
// showing as a steady deficit of the explicit error −½ m |b|² against the strain energy's
// second-order term. (An elastic bar whose halves meet at ±1 m/s, no walls or contact: the
// unbooked energy equals the kinetic gap to 1 % with every shape function.) At a node a wall set,
// both steps impose the wall's velocity, so no extra motion is booked there (the wall is the node's
// reference, as for the explicit error in contact_energy.cpp); a node whose fields were merged
// moves freely as one field. A contact exchange (stick or slide) leaves the node's welded motion
// to the forces, and the explicit error there is measured against the welded body; so is the extra
// motion. Projected back and exchanged again, the momenta would give the welded node the velocity
// Σ_f (m_f λ_f + (C a)_f) / M, M = Σ_f m_f, where the step moved it with Σ_f m_f (λ_f + a_f) / M:
// farther by Δt Σ_f (m_f a_f − (C a)_f) / M, on which the welded force Σ_f f_f works. Split as at
// a free node, where the welded increment V_b = Δt Σ_f f_f / M is a itself, half of that work is
// booked: ½ V_b·Σ_f (m_f a_f − (C a)_f). (Measuring the slide's tangential motion per field
// instead, against a welded normal, left 2.7 % of the quick 8 m/s three-grain column unbooked
// instead of 0.08 %.) So, with w = a at free and merged nodes, w = V_b at exchange nodes and
// w = 0 at wall nodes, the booked strain side is ½ Σ m w·a − ½ Σ_p m_p a_p·Σ_i S̄_ip w_i (C is
// symmetric, so (C a)_i = Σ_p S̄_ip m_p a_p and the second sum is gathered in G2P, no scatter).
// With the FLIP/PIC blend the FLIP share (1 − ζ) of it is booked; APIC moves the material with the
// velocity its particles carry and books none; grid damping changes a away from b and turns the
// term off (its energy is unbooked anyway).
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
double nodal_kinetic_energy_change(StepState<D>& state, double dt) {
  const NodeFields<D>& N = state.nodes;
  const double pic =
      state.problem.time.transfer == Transfer::apic ? 1.0 : state.problem.time.pic_fraction;
  const double negligible = state.negligible_mass;
  const std::int64_t nodes = static_cast<std::int64_t>(state.node_count());
  double change = 0.0, paired_increment = 0.0;
  const bool strain_gap = state.plan.books_strain_gap;
  const auto& touched = N.touched;
  for (int f = 0; f < state.fields(); ++f) {
    const auto& mass = N.mass[f];
    const auto& momentum = N.momentum[f];
    const auto& velocity = N.velocity[f];
    const auto& velocity_lumped = N.velocity_lumped[f];
    // Each field's sum starts from zero: OpenMP adds the threads' partial sums to the shared value
    // in the order the threads finish, which is exact for two partial sums and zero but not when
    // the first field's total is already there (a restart would then differ in the last bit).
    double field_change = 0.0, field_paired = 0.0;
#pragma omp parallel for reduction(+ : field_change, field_paired) schedule(static)
    for (std::int64_t i = 0; i < nodes; ++i) {
      const double m = mass[i];
      if (!(m > negligible)) continue;
      const Vec<D> lumped = momentum[i] / m;
      const Vec<D> received = velocity[i] - velocity_lumped[i];
      const double flip = m * (lumped.dot(received) + 0.5 * received.squaredNorm());
      const double projected = 0.5 * m * (velocity[i].squaredNorm() - lumped.squaredNorm());
      field_change += (1.0 - pic) * flip + pic * projected;
      if (!strain_gap) continue;
      switch (strain_side_pairing(touched, static_cast<std::size_t>(i))) {
        case StrainSidePairing::own:
          field_paired += 0.5 * m * received.squaredNorm();
          break;
        case StrainSidePairing::welded: {
          const WeldedNode<D> welded =
              welded_node(N, state.fields(), static_cast<std::size_t>(i), negligible);
          field_paired += 0.5 * m * (dt / welded.mass) * welded.force.dot(received);
          break;
        }
        case StrainSidePairing::none:
          break;
      }
    }
    change += field_change;
    paired_increment += field_paired;
  }
  state.strain_gap.nodal = paired_increment;
  return change;
}

template double nodal_kinetic_energy_change<2>(StepState<2>&, double);
template double nodal_kinetic_energy_change<3>(StepState<3>&, double);

}  // namespace fragmpm::mpm
