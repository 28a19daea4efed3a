#pragma once
// Per-step bookkeeping: energies, momentum, wall reactions (docs/design.md "Energy and momentum").
#include <array>
#include <cmath>
#include <string>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// What the particles removed after leaving the domain (`[grid] outside = "remove"`) carried out of
/// it, cumulative. The kinetic and stored strain energy enter the energy balance, so a removal does
/// not change balance_error (docs/design.md, "Energy and momentum bookkeeping").
struct LostParticles {
  long long count = 0;
  double mass = 0.0;                 ///< [kg per unit thickness in 2D]
  double kinetic = 0.0;              ///< ½ m |v|² (+ the affine part with APIC) at removal [J]
  double strain = 0.0;               ///< V₀ ψ (the stored, recoverable energy) at removal [J]
  std::array<double, 3> momentum{};  ///< Σ m v, components 0 … D−1 used [kg m/s]
};

/// Running totals that a restart must restore exactly.
struct EnergyAccumulators {
  double wall_work = 0.0;      ///< work done by walls on the material [J per unit thickness in 2D]
  double gravity_work = 0.0;   ///< work done by gravity [J]
  double load_work = 0.0;      ///< work done by traction loads [J]
  double friction_work = 0.0;  ///< dissipated by friction at walls and contacts [J]
  double dissipated = 0.0;     ///< dissipated by damage [J]
  /// Dissipated by the frictional flow of failed material (crushed_flow.hpp) [J].
  double flow_dissipation = 0.0;
  /// What grid contact and walls take out as perfectly plastic collisions, beyond the friction
  /// work (step/contact_energy.cpp) [J].
  double contact_dissipation = 0.0;
  /// Kinetic energy the grid-to-particle transfer removes: FLIP's smoothing of the nodal
  /// increments, PIC's projection (step/transfer_energy.cpp) [J].
  double transfer_dissipation = 0.0;
  double initial_energy = 0.0;  ///< kinetic + strain + fracture_energy at step 0 [J]
  /// Ψ_f, the crack energy of the phase field after the last solve ([KT19] eq. (3)) [J]. Not a
  /// running sum but a state (the energy the cracks hold), kept here because a restart cannot
  /// recompute it without the nodal field and must resume the balance exactly.
  double fracture_energy = 0.0;
  /// Phase field: Σ V₀ (g_old − g_new)(H − ψ⁺) over the steps, the energy the crack growth took
  /// from the history field H = max ψ⁺ beyond the tensile energy ψ⁺ its degradation released. The
  /// history field makes the model itself non-conservative where a cracking particle has unloaded
  /// since its peak (docs/design.md §2.5, "Energy"); the balance counts it as energy put in [J].
  double history_excess = 0.0;
  LostParticles lost;
};

/// One row of /series, recorded after each step.
template <int D>
struct SeriesRow {
  long long step = 0;
  double time = 0.0, dt = 0.0;
  double kinetic = 0.0, strain = 0.0, thermal = 0.0;
  EnergyAccumulators totals;
  /// (kinetic + strain + fracture_energy + dissipated + flow_dissipation + friction_work +
  /// contact_dissipation +
  /// transfer_dissipation + lost kinetic + lost strain) − (initial + wall_work + gravity_work +
  /// load_work + history_excess): zero for an
  /// exact conservative scheme. What remains is the explicit step's own energy error (large at
  /// nodes an impact accelerates). With APIC the kinetic energy includes the affine part ½ m tr(C Q
  /// Cᵀ).
  double balance_error = 0.0;
  Vec<D> momentum = Vec<D>::Zero();
  /// About the origin, Σ m_p (x_p × v_p + ε:(C_p Q_p)) with Q_p the second moment of the particle's
  /// domain: the spin of the affine field C_p counts with APIC [kg m²/s, per unit thickness in 2D].
  Axial<D> angular_momentum = Axial<D>::Zero();
  std::vector<Vec<D>>
      wall_force;  ///< reaction exerted by the material on each wall [N per unit thickness]
  std::vector<Vec<D>> wall_displacement;  ///< [m]
};

/// The scale the balance error is quoted against: the energy the run started with plus the work
/// done on it by walls, gravity and loads, each counted by magnitude so that a wall that takes
/// energy out still counts as a channel [J per unit thickness in 2D].
template <int D>
double energy_input(const SeriesRow<D>& row) {
  return row.totals.initial_energy + std::abs(row.totals.wall_work) +
         std::abs(row.totals.gravity_work) + std::abs(row.totals.load_work);
}

}  // namespace fragmpm::mpm
