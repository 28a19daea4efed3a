// The energy contact and walls take out of a step, booked as contact_dissipation.
//
// With l = p/m the lumped velocity a field brings to a node, b = Δt f/m its force increment, v its
// velocity after contact and walls and a the increment the particles receive (FLIP: v minus the
// lumped velocity after contact; they differ from l only where fields merged), the step changes
// kinetic + strain − external work by
//     Σ_i N_i − G,  N_i = Σ_f m (l·a − b·v + ½|a|²)  (FLIP),  ½ m (|v|² − |l|²) − m b·v  (APIC),
// to first order in the stress: the particles' kinetic energy moves by Σ m l·a + ½ Σ_p m_p|Σ S̄ a|²
// (FLIP) and the strain energy of update-stress-last by −Δt Σ f·v. G ≥ 0 is the transfer's Jensen
// gap (the particles see a node's change smeared by S̄). At a node no contact touched, a = b and
// v = l + b give N = −½ m |b|², the explicit step's own error; a field stopped against a fixed wall
// gives N = −½ m |l|², the kinetic energy it brought. Two fields that contact makes move as one
// (stick, or the merge of a node that is not separable) would, welded into one body, carry the
// single field's explicit error E_i = −½ M |V_b|², M = Σ_f m, V_b = Σ_f m b / M; what contact
// adds to that is, for a stick, N_i − E_i = −½ m_red |l_a − l_b|², the plastic collision of the
// lumped velocities, and for a FLIP merge zero (the particles keep their own velocities). The
// explicit error belongs with the rest of the scheme's error in balance_error, where the strain
// energy's second-order term balances it; booked as contact loss it made a triple junction
// "create" 2 % of its input. At a node a wall changed, the welded reference is the wall (E_i = 0).
// So the plastic loss of the collisions is
//     contact_dissipation += W_walls − friction − Σ_touched (N_i − E_i).
// The explicit error at the other nodes stays in balance_error; the transfer gap G is booked as
// transfer_dissipation (transfer_energy.cpp), at the contact nodes against the same welded body.
// The FLIP/PIC blend ζ weighs the two forms of N by 1 − ζ and ζ.
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
void book_contact_energy(StepState<D>& state, double dt, double friction_before,
                         double wall_work_before) {
  const NodeFields<D>& N = state.nodes;
  const double pic =
      state.problem.time.transfer == Transfer::apic ? 1.0 : state.problem.time.pic_fraction;
  const int fields = state.fields();
  const std::size_t nodes = state.node_count();
  double energy =
      0.0;  // Σ_touched (N_i − E_i), summed in node order (independent of the thread count)
  for (std::size_t i = 0; i < nodes; ++i) {
    if (!N.touched[i]) continue;
    for (int f = 0; f < fields; ++f) {
      const double m = N.mass[f][i];
      if (!(m > state.negligible_mass)) continue;
      const Vec<D> lumped = N.momentum[f][i] / m;
      const Vec<D> increment = dt * N.force[f][i] / m;
      const Vec<D>& velocity = N.velocity[f][i];
      const Vec<D> received = velocity - N.velocity_lumped[f][i];
      const double flip =
          m * (lumped.dot(received) - increment.dot(velocity) + 0.5 * received.squaredNorm());
      const double apic =
          0.5 * m * (velocity.squaredNorm() - lumped.squaredNorm()) - m * increment.dot(velocity);
      energy += (1.0 - pic) * flip + pic * apic;
    }
    if (N.touched[i] & touched_by_wall) continue;
    const WeldedNode<D> welded = welded_node(N, fields, i, state.negligible_mass);
    if (welded.mass > 0.0)
      energy += 0.5 * dt * dt * welded.force.squaredNorm() / welded.mass;  // − E_i
  }
  const double friction = state.totals.friction_work - friction_before;
  const double wall_work = state.totals.wall_work - wall_work_before;
  state.totals.contact_dissipation += wall_work - friction - energy;
}

template void book_contact_energy<2>(StepState<2>&, double, double, double);
template void book_contact_energy<3>(StepState<3>&, double, double, double);

}  // namespace fragmpm::mpm
