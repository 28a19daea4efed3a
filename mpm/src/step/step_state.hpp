#pragma once
// The state one explicit step works on: the problem with its particles, the active grid and its
// per-field node arrays, the partition and contact sums, and the energy accumulators. Every stage
// (one file each in this folder) is a free function over a StepState; solver.cpp owns one and
// calls the stages in the order of the step.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include "fragmpm/mpm/damage_field.hpp"
#include "fragmpm/mpm/grid_index.hpp"
#include "fragmpm/mpm/neo_hookean.hpp"
#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/mpm/series.hpp"
#include "fragmpm/mpm/shape_functions.hpp"
#include "fragmpm/mpm/wave_speed.hpp"
#include "step/phase_field_state.hpp"
#include "step/thermal_state.hpp"

namespace fragmpm::mpm {

/// Which stages the step runs; fixed at setup from the scene (plan_modules logs the reasons).
struct StepPlan {
  bool partitioned = false;         ///< two velocity fields per node may exist
  bool by_bodies = false;           ///< the fields are the bodies, always separable
  bool damage = false;              ///< some material has a damage law
  bool needs_contact_area = false;  ///< adhesion or contact conductance scale with the contact area
  bool gap_test = false;            ///< position test of contact ([NBS18] eq. (8))
  bool wall_gap_test = false;       ///< a contact wall tests the material's position (walls.cpp)
  bool principal_rule = false;      ///< nodal gradient = principal direction of the gradient tensor
  bool books_contact = false;       ///< two-field nodes or walls exist: book the contact energy
  /// FLIP without grid damping: book the strain side of the transfer gap (transfer_energy.cpp)
  bool books_strain_gap = false;
  bool phase_field = false;  ///< some material has the phase-field law: the nodal solve runs
};

/// Bits of NodeFields::touched: which stage changed a node's velocities this step.
/// touched_by_merge marks a contact node whose fields contact moved as one body without an
/// exchange (not separable, or only the second field has mass): its velocity is still its lumped
/// velocity plus its force increment, as at a node nothing touched.
inline constexpr std::uint8_t touched_by_contact = 1, touched_by_wall = 2, touched_by_merge = 4;

/// Which force increment the strain side of the transfer gap pairs with the particles'
/// increments at node i (transfer_energy.cpp). touched is empty while the plan books no contact
/// energy: then nothing touched any node.
enum class StrainSidePairing : std::uint8_t {
  own,     ///< nothing changed the node, or contact merged its fields: a = b, the field's own
  welded,  ///< a contact exchange: the welded body's Δt Σ f / Σ m, the reference of the explicit
           ///< error E (contact_energy.cpp)
  none,    ///< a wall set the velocity: the wall is the reference, nothing to book
};
inline StrainSidePairing strain_side_pairing(const std::vector<std::uint8_t>& touched,
                                             std::size_t i) {
  if (touched.empty()) return StrainSidePairing::own;
  const std::uint8_t t = touched[i];
  if (t & touched_by_wall) return StrainSidePairing::none;
  if ((t & touched_by_contact) && !(t & touched_by_merge)) return StrainSidePairing::welded;
  return StrainSidePairing::own;
}

/// The two sums of one step's strain-side transfer gap (transfer_energy.cpp), FLIP only; w is
/// the force increment of strain_side_pairing.
struct StrainGapSums {
  double nodal = 0.0;      ///< Σ over nodes and fields of ½ m w·a [J per unit thickness]
  double particles = 0.0;  ///< ½ Σ_p m_p a_p · Σ_i S̄_ip w_i, filled by G2P
};

/// Per node and field (field 1 exists only when the step is partitioned).
template <int D>
struct NodeFields {
  std::array<std::vector<double>, 2> mass;
  std::array<std::vector<Vec<D>>, 2> momentum, force;
  std::array<std::vector<Vec<D>>, 2> velocity_lumped;  ///< p_i / m_i before the grid update
  std::array<std::vector<Vec<D>>, 2> velocity;         ///< after the grid update, contact and walls
  /// Σ S̄ m_p x_p per field, only while a wall has gap_test (plan.wall_gap_test).
  std::array<std::vector<Vec<D>>, 2> position;
  /// touched_by_contact | touched_by_wall where contact or a wall changed a field's velocity this
  /// step (kept while the plan books contact energy).
  std::vector<std::uint8_t> touched;
};

/// The mass and force of node i's fields welded into one body (fields lighter than `negligible`
/// left out).
template <int D>
struct WeldedNode {
  double mass = 0.0;
  Vec<D> force = Vec<D>::Zero();
};
template <int D>
WeldedNode<D> welded_node(const NodeFields<D>& N, int fields, std::size_t i, double negligible) {
  WeldedNode<D> node;
  for (int f = 0; f < fields; ++f)
    if (N.mass[f][i] > negligible) {
      node.mass += N.mass[f][i];
      node.force += N.force[f][i];
    }
  return node;
}

/// Race-free, thread-count-independent scatter: particles binned into strips along direction 0
/// wider than twice any stencil's reach, so strips of equal parity never share a node. Even strips
/// scatter in parallel, then odd ones; within a strip particles go in index order, so every node
/// sums its contributions in the same order whatever the number of threads.
struct ScatterOrder {
  std::int64_t strip_width = 3;      ///< cells per strip
  double largest_half_extent = 0.0;  ///< largest stencil half-extent along direction 0 [cells]
  std::vector<std::int64_t> strip_start, strip_order, strip_of, strip_cursor;
};

/// Damage-field-gradient partitioning ([HH17] §2.1-2.3, Alg. 1-2); allocated only when partitioned.
template <int D>
struct PartitionState {
  bool this_step = false;  ///< some particle has d̂ > 0 (or the fields are bodies)
  NeighbourLists<D> neighbours;
  std::vector<double> particle_dhat, particle_field;  ///< d̂_p = max(s_p, d_p), D̄(x_p)
  std::vector<Vec<D>> particle_gradient;              ///< ∇D̄(x_p) ([HH17] eq. (17)-(19))
  std::vector<Vec<D>> node_gradient;                  ///< nonlocal nodal ∇D̄_i ([HH17] Alg. 1)
  std::vector<Mat<D>> node_gradient_tensor;  ///< Σ_p ∇D̄_p ⊗ ∇D̄_p (principal rule only)
  /// For the junction rule of field_of: the largest damage d mapping to the node, and per field the
  /// sums Σ S̄ d̂_p x_p and Σ S̄ d̂_p over the band particles whose gradient decides their field there.
  std::vector<double> node_damage_max;
  std::array<std::vector<Vec<D>>, 2> node_side_moment;
  std::array<std::vector<double>, 2> node_side_weight;
  /// The field of every particle-node pair of this step, decided once by the partition stage:
  /// entry p · Stencil<D>::capacity + e is the field of particle p at its stencil entry e.
  std::vector<std::uint8_t> field_map;
};

/// Sums at nodes that can hold two fields (the nodes with a nodal damage gradient), and what the
/// contact stage books there.
template <int D>
struct ContactSums {
  std::array<std::vector<Vec<D>>, 2> mass_gradient;  ///< Σ m_p ∇S̄_ip per field ([XLS21] eq. (74))
  std::array<std::vector<double>, 2> dhat;  ///< Σ S̄ m_p d̂_p per field ([XLS21] eq. (70))
  std::array<std::vector<Vec<D>>, 2> volume_gradient;  ///< Σ V_p ∇S̄_ip per field (contact area)
  std::array<std::vector<Vec<D>>, 2> position;  ///< Σ S̄ m_p x_p per field ([NBS18] eq. (8))
  std::vector<double> dhat_max;                 ///< largest d̂ mapping to the node
  std::vector<std::int64_t> two_field_nodes;
  std::vector<double> friction_work, normal_impulse, area;  ///< per two-field node
  long long nodes_in_contact = 0;
};

/// Scratch of the wall stage: one entry per candidate node of the wall being applied.
template <int D>
struct WallScratch {
  std::vector<std::int64_t> nodes;
  std::vector<Vec<D>> impulse;
  std::vector<double> work, friction;
};

/// A particle that leaves the domain faster than this many times the largest wave speed of the
/// scene's materials stops the run even with `[grid] outside = "remove"`: fragments fly off at
/// speeds of the order of the impact and wave speeds, while an unstable step accelerates a particle
/// without bound, so such a departure is a failure, not a fragment.
inline constexpr double departure_speed_factor = 10.0;

template <int D>
struct StepState {
  Problem<D> problem;
  StepPlan plan;
  std::vector<NeoHookean> models;
  std::vector<ElasticLaw> elastic_laws;  ///< per material, for the wave speed of the step limit
  /// Per material: 0 no damage, 1 a damage law of damage_law.hpp, material_phase_field (2) the
  /// phase field. The constitutive update reads this one byte per particle to pick its branch.
  std::vector<char> material_damages;
  /// Per material: the Rankine law runs on the nonlocal σ̄₁ (RankineSoftening::nonlocal).
  std::vector<char> material_nonlocal;
  /// Per material: its failed particles (d = 1) keep no deviatoric stress, so their stress depends
  /// on J alone and their CPDI domain is kept square (failed_domain.hpp).
  std::vector<char> material_failed_fluid;
  bool nonlocal_damage = false;  ///< some material is nonlocal: G2P defers its constitutive update
  /// Per material: sin φ of the friction angle its failed particles flow at (crushed_flow.hpp), 0
  /// when they keep ψ⁻ without a bound. Any nonzero entry makes Particles::plastic_inverse exist.
  std::vector<double> crushed_sine;
  /// Nonlocal materials only: the trial largest principal stress σ₁ of each particle, then its
  /// kernel average σ̄₁ [Pa] (nonlocal_damage.cpp).
  std::vector<double> local_equivalent, nonlocal_equivalent;
  double time = 0.0;
  long long step = 0;
  EnergyAccumulators totals;
  SeriesRow<D> row;
  double next_dt_limit = 0.0;  ///< CFL limit from the state after the last step (C_cfl included)
  double negligible_mass = 0.0;
  double kernel_radius = 0.0;  ///< r_p of the damage field = cell diagonal ([HH17] §2.2) [m]
  /// departure_speed_factor × the largest wave speed √((K + 4G/3)/ρ₀) of the materials [m/s]
  double departure_speed_limit = 0.0;

  GridIndex<D> grid;
  NodeFields<D> nodes;
  ScatterOrder order;
  PartitionState<D> partition;
  ContactSums<D> contact;
  WallScratch<D> wall_scratch;
  std::vector<Vec<D>> load_force;  ///< f_p of this step [N per unit thickness in 2D]
  /// Penalty-wall force on each particle this step; empty unless the scene has a penalty wall.
  std::vector<Vec<D>> penalty_force;
  std::vector<double> penalty_measure;  ///< scratch: A_p of the penalty wall being applied
  bool penalty_walls = false;           ///< some wall is a penalty wall
  StrainGapSums strain_gap;  ///< this step's, while the plan books it (plan.books_strain_gap)
  /// Per-thread sums of G2P: momentum (D) and angular momentum (1 in 2D, 3 in 3D) per thread.
  std::vector<double> momentum_parts;
  /// The energy per reference volume a unit of damage released in the last constitutive update
  /// (the mean of ψ_t over the step, see constitutive_update.hpp; thermal and damage only): the
  /// damage heat of the next thermal stage is booked from it.
  std::vector<double> degradable;
  /// ψ_t per particle at the end of the last constitutive update (damage laws only): the start of
  /// the next step's release, whose dissipation takes the mean of ψ_t over the step.
  std::vector<double> release_before;
  /// Thermal module with crushed flow only: the energy per reference volume the particle's flow
  /// dissipated this step [J/m³], heat for the thermal stage, which consumes it.
  std::vector<double> flow_heat;
  std::unique_ptr<ThermalState<D>> thermal;         ///< exists only when the scene needs it
  std::unique_ptr<PhaseFieldState<D>> phase_field;  ///< exists only with a phase-field material

  int fields() const { return partition.this_step ? 2 : 1; }
  std::size_t node_count() const { return nodes.mass[0].size(); }
};

/// Sets v to n copies of value without giving memory back; grows with 25 % headroom, so an active
/// region that creeps by a few nodes does not reallocate every step.
template <class T>
void reset_array(std::vector<T>& v, std::size_t n, const T& value) {
  if (v.capacity() < n) v.reserve(n + n / 4);
  v.assign(n, value);
}

/// The same without initialising (every entry is written before it is read).
template <class T>
void size_array(std::vector<T>& v, std::size_t n) {
  if (v.capacity() < n) v.reserve(n + n / 4);
  v.resize(n);
}

}  // namespace fragmpm::mpm
