#pragma once
// The stages of one explicit step, in the order solver.cpp calls them. Each is defined in the file
// of its name in this folder and instantiated there for D = 2, 3 and every shape function.
#include <cstdint>
#include <optional>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "step/step_state.hpp"

namespace fragmpm::mpm {

/// Active region = nodes touched by any particle's stencil plus one node of padding; fails when a
/// particle left the computational domain. (active_region.cpp)
template <int D>
std::optional<NumericalFailure> update_active_region(StepState<D>& state);
/// Sizes the node arrays of this step's fields and zeroes the sums. (active_region.cpp)
template <int D>
void size_grid(StepState<D>& state);
/// Counting sort of particles into scatter strips (stable: index order within a strip).
template <int D>
void bin_particles_into_strips(StepState<D>& state);
/// f_p of this step's traction loads. (active_region.cpp)
template <int D>
void update_load_forces(StepState<D>& state);

/// Particle forces of the penalty walls ([XLS21] eq. (83), (86)-(87)) into penalty_force, and
/// their reactions into the series row. (penalty_walls.cpp)
template <int D>
void apply_penalty_walls(StepState<D>& state);

/// The phase field of this step ([KT19] §4.2-4.3, Alg. 1): assembles [KT19] eq. (56)-(57) from
/// the particles' history field over this step's grid (active region and strips already built),
/// solves it by conjugate gradients, and sets d and the crack energy Ψ_f (totals.fracture_energy).
/// (phase_field_stage.cpp)
template <int D, ShapeFunctionKind Kind>
void solve_phase_field(StepState<D>& state);

/// d̂_p and the kernel damage field with its gradient ([HH17] eq. (17)-(19)); sets
/// partition.this_step. (damage_field_stage.cpp)
template <int D>
void update_damage_field(StepState<D>& state);
/// Nodal damage gradient, band sides and the field map of this step ([HH17] Alg. 1-2).
/// (partition.cpp)
template <int D, ShapeFunctionKind Kind>
void partition_nodes(StepState<D>& state);

/// P2G ([XLS21] eq. (47)-(49)) into the fields of the field map; Affine adds the APIC momentum
/// of C_p ([JSS15]). (scatter.cpp)
template <int D, ShapeFunctionKind Kind, bool Partitioned, bool Affine>
void scatter_to_grid(StepState<D>& state);
/// Lumped and updated nodal velocities. (grid_update.cpp)
template <int D>
void update_grid_velocities(StepState<D>& state, double dt);
/// Two-field nodes: move as one or exchange momentum through the contact law. (contact_nodes.cpp)
template <int D>
void exchange_contact_momentum(StepState<D>& state, double dt);
/// Rigid walls on their candidate nodes. (walls.cpp)
template <int D>
void apply_walls(StepState<D>& state, double dt);

/// What contact and walls took from the mechanical energy this step, booked as
/// contact_dissipation. (contact_energy.cpp)
template <int D>
void book_contact_energy(StepState<D>& state, double dt, double friction_before,
                         double wall_work_before);

/// The particles' kinetic energy after G2P as the nodes give it, less the starting kinetic energy:
/// Σ_i (1 − ζ)(m l·a + ½ m|a|²) + ζ ½ m (|v|² − |l|²). The particles end with less by the
/// transfer's smoothing, booked as transfer_dissipation. With plan.books_strain_gap also fills
/// strain_gap.nodal, the nodal half of the strain side of that loss. (transfer_energy.cpp)
template <int D>
double nodal_kinetic_energy_change(StepState<D>& state, double dt);

/// Nodal capacities and temperatures θⁿ, before the grid update. (thermal_stage.cpp)
template <int D, ShapeFunctionKind Kind, bool Partitioned>
void thermal_begin(StepState<D>& state);
/// Heat loads, nodal rates and particle temperatures θⁿ⁺¹, after contact and walls.
/// (thermal_stage.cpp)
template <int D, ShapeFunctionKind Kind, bool Partitioned>
void thermal_finish(StepState<D>& state, double dt);

/// G2P ([XLS21] eq. (64)-(66)), FLIP or (Affine) APIC, and the constitutive update that closes
/// the step. (g2p.cpp)
template <int D, ShapeFunctionKind Kind, bool Partitioned, bool Thermal, bool Affine>
std::optional<NumericalFailure> grid_to_particles(StepState<D>& state, double dt);

/// Energy sums of a constitutive pass [J per unit thickness in 2D].
struct ConstitutiveSums {
  double stored = 0.0;      ///< Σ V₀ (ψ − d ψ_t)
  double dissipated = 0.0;  ///< Σ V₀ Δd ψ_t
  double flowed = 0.0;      ///< Σ V₀ of the energy failed material's flow released
};

/// The constitutive update of the particles of nonlocal Rankine materials, after G2P has stored
/// their trial σ₁ in state.local_equivalent: the kernel average σ̄₁ over the cell-diagonal
/// neighbourhood drives their damage law. `limit_domains`: CPDI, keep failed domains within a
/// cell. (nonlocal_damage.cpp)
template <int D, bool Thermal>
ConstitutiveSums nonlocal_constitutive_update(StepState<D>& state, double dt, bool limit_domains);

/// With `[grid] outside = "remove"`, after the step: books and removes the particles whose
/// position left [grid.min, grid.max], and recomputes the next step's Δt limit without them. A
/// departure with a non-finite state or faster than departure_speed_factor times the largest wave
/// speed of the scene's materials is a numerical failure. (departures.cpp)
template <int D>
std::optional<NumericalFailure> remove_departed_particles(StepState<D>& state, double dt);
/// Renumbers the particle lists of traction and heat loads: particle k becomes new_index[k], and
/// entries with new_index[k] < 0 are dropped. (departures.cpp)
template <int D>
void remap_particle_references(Problem<D>& problem, const std::vector<std::int64_t>& new_index);

}  // namespace fragmpm::mpm
