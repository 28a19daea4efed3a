#pragma once
// Rigid-block oracle of the sliding-block verification V2 ([NBS18] §3, Fig. 2, appendix eq.
// (46)-(54)). A block of height h and length l (per unit thickness) pressed by a normal stress N
// and pushed by a tangential stress S(t) = R N (t − t₂)/t_s (t > t₂, eq. (46)) slides on a fixed
// base once S reaches the static resistance; the friction traction is S_slide = μ(v) N + S_a (eq.
// (41)).
#include <optional>

#include "fragmpm/mpm/friction_law.hpp"

namespace fragmpm::pipeline {

/// Loading and block of the sliding-block problem; all SI.
struct SlidingBlockLoading {
  double density = 0.0;           ///< ρ [kg/m³]
  double height = 0.0;            ///< h [m]
  double length = 0.0;            ///< l [m]
  double normal_stress = 0.0;     ///< N [Pa], reached at t₁ and held
  double ratio = 1.0;             ///< R = S(t_f)/N
  double normal_ramp_end = 0.0;   ///< t₁ [s]
  double tangential_start = 0.0;  ///< t₂ [s]
  double end_time = 0.0;          ///< t_f [s]; t_s = t_f − t₂
};

/// The loading of [NBS18] §3: t₁ = t₂ = `ramp_fraction` t_f and N, t_f chosen so that a Coulomb
/// block (coefficient μ) has slid `distance` [m] at t_f with speed `final_speed` [m/s]. With k =
/// S_a = 0 eq. (50) gives v = αT²/2, x = αT³/6, so T = 3x/v, t_s = T/(1 − μ/R) (eq. (47)), t_f =
/// t_s/(1 − fraction), α = 2v/T² and N = α ρ h t_s / R (eq. (49)).
SlidingBlockLoading sliding_block_loading(double density, double height, double length,
                                          double coulomb_coefficient, double ratio,
                                          double final_speed, double distance,
                                          double ramp_fraction);

/// The friction family of the appendix: onset when S = μ_s N + S_a (eq. (47)), then
/// S_slide = (μ_d + k v) N + S_a (eq. (41), (48)).
struct RigidBlockFriction {
  double static_coefficient = 0.0;   ///< μ_s
  double dynamic_coefficient = 0.0;  ///< μ_d
  double slope = 0.0;                ///< k [s/m]
  double adhesion = 0.0;             ///< S_a [Pa]
};

/// The closed-form family of a friction law: Coulomb, velocity-dependent, adhesion (its tensile
/// strength does not enter) and the sharp static/dynamic law (v½ = 0); nullopt for the smooth law
/// with v½ > 0 and for thermal softening (use integrate_rigid_block).
std::optional<RigidBlockFriction> rigid_block_friction(const mpm::FrictionLaw& law);

/// Onset of sliding t_i = t₂ + (μ_s + S_a/N) t_s / R (eq. (47)) [s]; +inf if the block never
/// slides.
double rigid_block_onset(const SlidingBlockLoading& loading, const RigidBlockFriction& friction);

/// Block velocity at time t (eq. (50)-(51)) [m/s]; 0 before the onset.
double rigid_block_velocity(const SlidingBlockLoading& loading, const RigidBlockFriction& friction,
                            double t);

/// Friction work per unit thickness Q/b = l ∫ S_slide v dt from the onset to t (eq. (52)-(53); for
/// k ≠ 0 our own integration of eq. (52) with eq. (50)) [J/m].
double rigid_block_friction_work(const SlidingBlockLoading& loading,
                                 const RigidBlockFriction& friction, double t);

/// The rigid block with any friction law, S_slide = μ(v) N (+ S_a for adhesion; θ = θ_ref for
/// thermal softening), integrated from the onset by classical Runge-Kutta with `steps` steps.
struct RigidBlockState {
  double onset = 0.0;          ///< [s]
  double velocity = 0.0;       ///< [m/s]
  double distance = 0.0;       ///< slid [m]
  double friction_work = 0.0;  ///< per unit thickness [J/m]
};
RigidBlockState integrate_rigid_block(const SlidingBlockLoading& loading,
                                      const mpm::FrictionLaw& law, double t, int steps);

}  // namespace fragmpm::pipeline
