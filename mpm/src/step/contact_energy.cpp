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
// gives N = −½ m |l|², the kinetic energy it brought. So the energy of the nodes contact touched,
// less the walls' work and the friction work, is the plastic loss of the collisions:
//     contact_dissipation += W_walls − friction − Σ_touched N_i.
// The explicit error at the other nodes stays in balance_error; the transfer gap G is booked as
// transfer_dissipation (transfer_energy.cpp). The FLIP/PIC blend ζ weighs the two forms of N by
// 1 − ζ and ζ.
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
  double energy = 0.0;  // Σ_touched N_i, summed in node order (independent of the thread count)
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
  }
  const double friction = state.totals.friction_work - friction_before;
  const double wall_work = state.totals.wall_work - wall_work_before;
  state.totals.contact_dissipation += wall_work - friction - energy;
}

template void book_contact_energy<2>(StepState<2>&, double, double, double);
template void book_contact_energy<3>(StepState<3>&, double, double, double);

}  // namespace fragmpm::mpm
