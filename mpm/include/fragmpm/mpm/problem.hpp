#pragma once
// The compiled scene: everything the solver needs, already in SI units and validated.
// The scene-file parser (pipeline/) fills this; the core never sees TOML or units.
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include "fragmpm/mpm/contact_exchange.hpp"
#include "fragmpm/mpm/damage_law.hpp"
#include "fragmpm/mpm/friction_law.hpp"
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/thermal_spec.hpp"
#include "fragmpm/mpm/velocity_history.hpp"

namespace fragmpm::mpm {

/// linear: multilinear hats; ugimp: hats convolved with an undeformed box [BK04]; cpdi: hats
/// averaged over the convected parallelogram domain [SBB11]; bspline2: the C¹ quadratic B-spline
/// of the grid (support three nodes per direction), the basis of [KT19] §4.
enum class ShapeFunctionKind { linear, ugimp, cpdi, bspline2 };

/// Compressible neo-Hookean ([XLS21] eq. (16)-(17)), given by bulk and shear modulus.
struct MaterialSpec {
  std::string name;
  double bulk_modulus = 0.0;   ///< K [Pa]
  double shear_modulus = 0.0;  ///< G [Pa]
  double density = 0.0;        ///< ρ0 [kg/m^3]
  DamageLaw damage = NoDamage{};
  Degradation degradation = Degradation::tensile_spectral;
  double strength = 0.0;  ///< uniform σ_f [Pa] (Particles::strength holds the per-particle value)
  bool weibull = false;   ///< strengths drawn from `weibull_strength` ([HH17] eq. (25))
  WeibullStrength weibull_strength;
  /// l_ch of the damage law [m]; 0 = the particle size V₀^(1/D) (the width of a one-particle crack
  /// band). The papers list l_ch as an input ([HH17] Tables II-III: 1.414 mm at h = 1 mm).
  double characteristic_length = 0.0;
  /// φ [rad] of failed particles (d = 1) as a cohesionless frictional solid
  /// (crushed_flow.hpp); 0 keeps the failed material's ψ⁻ without a bound. Hencky spectral only.
  double crushed_friction_angle = 0.0;

  bool damages() const { return !std::holds_alternative<NoDamage>(damage); }
};

/// Width of the crack band of Rankine softening in cells. Before a node becomes separable its
/// particles share one velocity field, so the strain localises in a band about a cell wide, not one
/// particle row: on the `bar-tension` verification case (2 × 2 particles per cell) a band formed
/// with l_ch = h dissipates 1.11, 1.06 and 1.11 × G_f per crack area at h = 0.5, 0.25 and 0.125 mm,
/// with l_ch = √2 h 0.86, 0.84 and 0.85, and with the particle size h/2 1.82, 1.91 and 2.23
/// (growing). Dissipation scales as l_ch^-0.73 between the first two, which puts G_f at l_ch =
/// 1.13 h; calibrated once there, as crack band theory [BO83] prescribes for a band whose width the
/// discretisation sets.
inline constexpr double rankine_band_cells = 1.13;

/// Width of the crack band of nonlocal Rankine softening in cells (RankineSoftening::nonlocal):
/// the averaging over the cell diagonal damages a band about two radii wide.
inline constexpr double rankine_nonlocal_band_cells = 4.1;

/// The characteristic length l_ch [m] of a particle of `material` with reference volume V₀ (an area
/// per unit thickness in 2D) on a grid of `cell_size` h: the material's `characteristic_length`
/// when the scene gives one; for Rankine softening the band width rankine_band_cells × h; for time
/// to failure the cell diagonal √D h of [HH17] §2.7, τ = l_ch / c_f. A particle ahead of a running
/// crack starts to fail before the one behind it has finished, so a crack does not advance one
/// particle per τ: measured on the pulled bar (`fragmpm verify bar-tension`), τ from the cell
/// diagonal runs the crack at 0.99 and 1.07 c_f at h = 0.5 and 0.25 mm, τ from the particle size
/// at 1.41 and 1.45 c_f. The one definition behind the damage update (the softening modulus
/// [XLS21] eq. (20)-(21) and τ of [HH17] eq. (24)), the scene compiler's snap-back check and its
/// count of Weibull draws above the snap-back limit.
template <int D>
inline double characteristic_length(const MaterialSpec& material, double reference_volume,
                                    double cell_size) {
  if (material.characteristic_length > 0.0) return material.characteristic_length;
  if (const auto* rankine = std::get_if<RankineSoftening>(&material.damage))
    return (rankine->nonlocal ? rankine_nonlocal_band_cells : rankine_band_cells) * cell_size;
  (void)reference_volume;
  return std::sqrt(double(D)) * cell_size;
}

/// The bulk modulus K* that turns the 2D Hencky energy ψ = ½λ(tr ε)² + μ Σ εᵢ² into its
/// plane-stress form. With τ_zz = λ tr ε + 2μ ε_zz = 0 the out-of-plane log strain is ε_zz = −λ (ε₁
/// + ε₂)/(λ + 2μ), and eliminating it leaves ψ = ½λ*(ε₁ + ε₂)² + μ(ε₁² + ε₂²) with λ* = 2λμ/(λ +
/// 2μ), exactly, since ψ is quadratic in the log strains. A 2D Hencky material with K* = λ* + 2μ/3
/// in place of K is therefore the plane-stress material: uniaxial stress gives Young's modulus E
/// and lateral strain −ν, and its P-wave modulus λ* + 2μ is the plate's E/(1 − ν²). The
/// tension–compression split ([KT19] eq. (14)) then acts on the in-plane strains ε₁, ε₂ with λ*.
inline double plane_stress_bulk_modulus(double bulk_modulus, double shear_modulus) {
  const double lambda = bulk_modulus - 2.0 * shear_modulus / 3.0;
  const double plane_lambda = 2.0 * lambda * shear_modulus / (lambda + 2.0 * shear_modulus);
  return plane_lambda + 2.0 * shear_modulus / 3.0;
}

/// contact: one-sided, frictional (Coulomb μ = friction); roller: bilateral normal constraint, free
/// tangentially; fixed: the material moves with the wall; penalty: one-sided and frictionless, a
/// particle force κ_n × (the part of the particle's domain behind the plane) ([XLS21] eq. (83),
/// (86)-(87); fragmpm/mpm/penalty_contact.hpp), which sees gaps smaller than a cell.
enum class WallKind { contact, roller, fixed, penalty };

/// A rigid plane through `point` (at t = 0) with unit `normal` pointing into the material side.
template <int D>
struct WallSpec {
  std::string name;
  Vec<D> point = Vec<D>::Zero();   ///< [m]
  Vec<D> normal = Vec<D>::Zero();  ///< unit
  WallKind kind = WallKind::contact;
  FrictionLaw friction = CoulombFriction{};  ///< contact walls only
  VelocityHistory<D> velocity;
  WallRegion<D> region;  ///< nodes the wall acts on
  /// Penalty walls only: κ_n of [XLS21] eq. (83), contact pressure per penetration depth [Pa/m].
  double penalty_stiffness = 0.0;
  /// Contact walls only: a node touches the wall when its material does, i.e. when the
  /// mass-weighted position of each field's particles at the node is within wall_gap_cells cells
  /// of the plane ([NBS18] eq. (8) with the wall as a partner of zero extent), instead of when
  /// the node itself lies behind the plane (walls.cpp says why).
  bool gap_test = false;
};

/// Distance from a contact wall's plane, in cells, within which a field's material position at a
/// node counts as touching: half of the 0.8 h that [NBS18] eq. (8) allows between the material
/// positions of two fields, whose surfaces each lie about 0.4 h beyond them.
inline constexpr double wall_gap_cells = 0.4;

/// A surface traction on part of a body's boundary, applied as particle forces f_p = t(τ) a_p with
/// a_p the boundary length (2D) or area (3D) the particle carries. t is piecewise linear in time
/// through (times, tractions) and constant outside them.
template <int D>
struct TractionLoad {
  std::string name;
  std::vector<std::int64_t> particles;   ///< loaded particles
  std::vector<double> boundary_measure;  ///< a_p per loaded particle [m in 2D, m² in 3D]
  std::vector<double> times;             ///< [s], increasing
  std::vector<Vec<D>> tractions;         ///< [Pa] at `times`

  Vec<D> traction(double t) const {
    if (times.empty()) return Vec<D>::Zero();
    if (t <= times.front()) return tractions.front();
    for (std::size_t k = 1; k < times.size(); ++k)
      if (t <= times[k]) {
        const double s = (t - times[k - 1]) / (times[k] - times[k - 1]);
        return (1.0 - s) * tractions[k - 1] + s * tractions[k];
      }
    return tractions.back();
  }
};

/// Damage-field-gradient partitioning and contact between the two fields of a node (docs/design.md;
/// [HH17] §2.2-2.4, Alg. 1-3; [XLS21] eq. (67)-(77)).
enum class Partitioning {
  automatic,  ///< on when the scene has more than one body or a damaging material
  off,        ///< one velocity field everywhere (the "single-field" comparison runs)
  bodies,  ///< field = (body ≠ 0), always separable: a-priori multimaterial contact ([NBS18] §2.2),
           ///< the two-body reference of the self-contact check ([HH17] §3.1)
};

/// How the nonlocal nodal damage-field gradient is formed from the particle gradients.
enum class NodalGradientRule {
  principal,  ///< principal direction of Σ_p ∇D̄_p ⊗ ∇D̄_p ([HH17] §2.2's maximisation; default)
  largest,  ///< the particle gradient of largest norm ([HH17] Alg. 1)
};

template <int D>
struct ContactSpec {
  Partitioning partitioning = Partitioning::automatic;
  FrictionLaw friction = CoulombFriction{};  ///< between the two fields of a separable node
  /// Separable when the largest d̂ = max(s, d) of a particle mapping to the node reaches
  /// `critical_damage` ([HH17] §2.3: "at least one particle fully damaged") and the mass-weighted
  /// mean d̂ of each field exceeds `minimum_damage` ([HH17] eq. (21), Alg. 3; [XLS21] eq.
  /// (70)-(71)).
  double critical_damage = 1.0;  ///< D_cr
  double minimum_damage = 0.25;  ///< D_min ([HH17] Table III)
  /// Neighbour lists of the damage field are rebuilt once a particle has moved this fraction of
  /// the kernel radius since the last build ([HH17] §2.5).
  double rebuild_fraction = 0.25;
  /// Alg. 1's largest particle gradient follows the staircase of particle rows (up to 18° off a
  /// straight crack's normal in the tests, 7° for the principal direction), so principal is the
  /// default; largest is kept to reproduce the paper's algorithm.
  NodalGradientRule nodal_gradient = NodalGradientRule::principal;
  bool position_gap_test =
      false;  ///< also require overlapping extrapolated positions ([NBS18] eq. (8))
  /// Frictional heat per step at two-field nodes and contact walls: second order ([NBS18] eq.
  /// (31)-(36)) converges in Δt where first order (eq. (27)) needs a ten times smaller step
  /// ([NBS18] Fig. 7); both read the force-updated velocity, which at a light node is not the
  /// material's. Lumped slip (the default) takes the friction impulse on the slip of the lumped
  /// velocities, the particles' mean velocities at the node (contact_exchange.cpp).
  FrictionWorkOrder friction_work_order = FrictionWorkOrder::lumped_slip;
  Vec<D> normal = Vec<D>::Zero();  ///< prescribed contact normal of field 0; zero = from mass
                                   ///< gradients ([XLS21] eq. (74))
};

/// What a particle whose position leaves [grid.min, grid.max] does to the run (like LAMMPS's choice
/// for lost atoms).
enum class OutsidePolicy {
  stop,    ///< a numerical failure: the run stops with a diagnostic (exit code 3)
  remove,  ///< removed between steps; its mass, momentum and energy are booked as lost
};

template <int D>
struct GridSpec {
  double cell_size = 0.0;       ///< h [m]
  Vec<D> min = Vec<D>::Zero();  ///< lower corner of the computational domain [m]
  Vec<D> max = Vec<D>::Zero();  ///< upper corner [m]
  ShapeFunctionKind shape_function = ShapeFunctionKind::cpdi;
  OutsidePolicy outside = OutsidePolicy::stop;
};

/// How velocities go between particles and grid. FLIP ([XLS21] eq. (64)) lumps each particle's
/// momentum at its velocity, which misplaces the momentum of a rotation at partly filled nodes;
/// APIC ([JSS15]) carries the particle's affine velocity field C_p as well, so rigid and affine
/// motions pass the grid unchanged.
enum class Transfer { flip, apic };

struct TimeSpec {
  double cfl = 0.4;       ///< C_cfl in Δt = C h / max(c + |v|)
  double fixed_dt = 0.0;  ///< [s]; 0 = adaptive
  Transfer transfer = Transfer::flip;
  double pic_fraction = 0.0;  ///< FLIP only: ζ of [XLS21] eq. (64), 0 = pure FLIP, 1 = pure PIC
  /// ζ_θ for the particle temperatures: θ_p ← (1 − ζ_θ)(θ_p + Δt Σ S̄ θ̇_i) + ζ_θ Σ S̄ (θ_i + Δt θ̇_i).
  /// 0 is [XLS21] eq. (62), whose increment lets a particle hotter than the nodal interpolant warm
  /// further (7.8 K past the hottest initial temperature at a conductivity contrast of 10⁴); the
  /// PIC part is a convex combination of nodal temperatures and conserves the heat content exactly.
  double thermal_pic_fraction = 0.0;
  /// α of a mass-proportional damping force −α m v on the grid [1/s]; 0 = off (the default). For
  /// dynamic relaxation to a static state: each grid velocity update becomes
  /// v_i ← (v_i + Δt f_i/m_i) / (1 + α Δt) (step/grid_update.cpp), so a free rigid motion decays as
  /// (1 + αΔt)^(−n) → exp(−α t). The static solution does not depend on α. The energy it removes is
  /// not booked: with damping on, balance_error includes it.
  double damping = 0.0;
};

struct StopSpec {
  double end_time = std::numeric_limits<double>::infinity();  ///< [s]
  long long max_steps = std::numeric_limits<long long>::max();
  double platen_displacement = std::numeric_limits<double>::infinity();  ///< |displacement| [m]
  int platen = -1;  ///< wall index whose displacement is watched; -1 = none
};

struct OutputSpec {
  double interval = 0.0;            ///< [s] between frames; 0 = only first and last
  std::vector<std::string> fields;  ///< frame datasets to write (empty = all)
};

template <int D>
struct Problem {
  GridSpec<D> grid;
  TimeSpec time;
  StopSpec stop;
  OutputSpec output;
  Vec<D> gravity = Vec<D>::Zero();  ///< [m/s^2]
  /// 2D only: the bodies are thin plates, σ_zz = 0, instead of plane strain (ε_zz = 0). The scene
  /// compiler has then replaced each (Hencky) material's bulk modulus by plane_stress_bulk_modulus.
  bool plane_stress = false;
  std::vector<MaterialSpec> materials;
  std::vector<WallSpec<D>> walls;
  ContactSpec<D> contact;
  std::vector<TractionLoad<D>> loads;
  ThermalSpec<D> thermal;               ///< thermal module data; empty = module off
  std::vector<std::string> body_names;  ///< index = body id
  Particles<D> particles;
  std::string scene_path;  ///< where it came from (for messages and /meta)
  std::string scene_text;  ///< verbatim scene file, stored in /meta so a run can be restarted
};

}  // namespace fragmpm::mpm
