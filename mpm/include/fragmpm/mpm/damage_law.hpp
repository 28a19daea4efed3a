#pragma once
// Damage laws (docs/design.md "Damage laws"), chosen per material. Plain structs in a std::variant:
// the per-particle dispatch is a jump table, not a virtual call.
#include <variant>
#include <vector>

#include "fragmpm/mpm/neo_hookean.hpp"
#include "fragmpm/mpm/phase_field.hpp"
#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// No damage: the material stays elastic.
struct NoDamage {};

/// Rankine with mesh-regularised linear softening ([XLS21] eq. (19)-(21); [HH17] eq. (23)). The
/// strength σ_f is per particle (Particles::strength), so a Weibull field can replace the uniform
/// value.
struct RankineSoftening {
  double fracture_energy = 0.0;  ///< G_f [J/m²]
  double youngs_modulus = 0.0;  ///< E [Pa], for the brittleness H̄ = σ_f² / (2 E G_f) (eq. (21))
  /// Drive the law with the kernel average σ̄₁ of the trial largest principal stress over the
  /// particles within the cell diagonal ([PCB87]; docs/design.md "Nonlocal Rankine"), so the band
  /// the damage localises in is as wide as the averaging, not as one particle row.
  bool nonlocal = false;
};

/// Time to failure ([HH17] eq. (24)): once the largest principal stress reaches σ_f, d grows by
/// Δt/τ per step with τ = l_ch / c_f (the paper's "τ = c_f/ℓ" is a transit time, so ℓ/c_f).
struct TimeToFailure {
  double crack_speed = 0.0;  ///< c_f [m/s]
};

/// PhaseField (phase_field.hpp): the AT2 phase field of [KT19], solved on the grid each step; its
/// particle update (history field, split, degradation) is not update_damage's.
using DamageLaw = std::variant<NoDamage, RankineSoftening, TimeToFailure, PhaseField>;

/// How damage degrades the stress.
enum class Degradation {
  tensile_spectral,  ///< only tensile principal stresses scale by (1 − d) ([HH17] eq. (26)-(27))
  isotropic,         ///< σ = (1 − d) σ^E ([XLS21] eq. (7))
  /// ψ = ψ⁻ + (1 − d) ψ⁺ with ψ⁺ = W(b̄) + U(J)·[J > 1], ψ⁻ = U(J)·[J ≤ 1] ([AMM09]):
  /// shear and volumetric tension degrade, volumetric compression does not. Unlike the spectral
  /// split of the Cauchy stress, the degraded stress derives from a potential, so a damaged
  /// particle stores exactly the work done on it, and a failed one carries a pressure only.
  volumetric_deviatoric,
  /// ψ = ψ⁻ + (1 − d) ψ⁺ with Miehe's spectral split of the Hencky energy in the principal
  /// logarithmic strains ([KT19] eq. (14), phase_field.hpp): the material is Hencky-elastic (the
  /// neo-Hookean to O(ε²)), the stress derives from a potential, the energy released by Δd is
  /// exactly Δd ψ⁺, and a failed particle keeps its stiffness along compressed principal
  /// directions (shear included), so crushed material neither creates energy nor flows.
  hencky_spectral,
};

/// Weibull strength per particle ([HH17] eq. (25)): σ_f / σ̄_f = (V̄/V · ln ℛ / ln ½)^{1/m}.
struct WeibullStrength {
  double reference_strength = 0.0;  ///< σ̄_f [Pa]
  double reference_volume = 0.0;    ///< V̄ [m³]
  double modulus = 0.0;             ///< m
  double thickness = 0.0;           ///< out-of-plane thickness for V in 2D [m]
  unsigned long long seed = 0;
};

// ---------------------------------------------------------------------------------------------
// Damage mechanics (implemented in damage_law.cpp; D = 2 plane strain and D = 3 instantiated).

/// Mesh-regularised damage modulus H_s = H̄ l_ch / (1 − H̄ l_ch) with the brittleness
/// H̄ = σ_f² / (2 E G_f) ([XLS21] eq. (20)-(21)). `strength` σ_f [Pa], `characteristic_length` l_ch
/// [m]: the width of the band the damage localises in. The solver passes the particle size
/// V₀^(1/D), not the paper's cell diagonal: damage is a particle variable, so a crack localises in
/// one row of particles, and only l_ch = that row's width makes the band dissipate G_f per unit
/// crack area (with the cell diagonal and 2 particles per cell a one-row crack dissipates
/// G_f/(2√2)). Returns NaN when H̄ l_ch ≥ 1: the particle would have to snap back to dissipate G_f,
/// so no regularised softening exists at this particle size.
double rankine_softening_modulus(double strength, const RankineSoftening& law,
                                 double characteristic_length);

/// Largest characteristic length l_ch [m] with H̄ l_ch < 1 ([XLS21] eq. (21)): every l_ch strictly
/// below 1/H̄ = 2 E G_f / σ_f² is admissible.
/// The largest strength with a softening branch at this l_ch: √(2 E G_f / l_ch) [Pa] ([BO83]: the
/// strength a crack band of width l_ch must not exceed to dissipate G_f). The damage update caps
/// stronger particles' strength at it.
double rankine_largest_strength(const RankineSoftening& law, double characteristic_length);

double rankine_largest_characteristic_length(double strength, const RankineSoftening& law);

/// One damage update from the trial (undamaged, "effective") Cauchy stress σ̄ [Pa] of a particle
/// with strength σ_f [Pa] and characteristic length l_ch [m], over a step dt [s]. `history` keeps
/// the largest principal stress max_t σ̄₁ seen so far [Pa] (the R of [XLS21] eq. (19) is
/// max(σ_f, history)); `damage` is d ∈ [0, 1]; both are updated in place and never decrease.
///  * RankineSoftening: d = (1 + H_s)(1 − σ_f / R), capped at 1 ([XLS21] eq. (20)).
///  * TimeToFailure: once σ̄₁ has reached σ_f, d ← min(1, d + dt/τ) every step with τ = l_ch / c_f
///    ([HH17] eq. (24)), also after the stress has dropped again.
///  * NoDamage: nothing changes.
template <int D>
void update_damage(const DamageLaw& law, const Mat<D>& trial_stress, double strength,
                   double characteristic_length, double dt, double& history, double& damage);

/// The same update driven by a given equivalent stress σ₁ [Pa] in place of the trial stress's
/// largest principal value: the nonlocal Rankine law passes the kernel average σ̄₁ here.
void update_damage_from_equivalent(const DamageLaw& law, double equivalent_stress, double strength,
                                   double characteristic_length, double dt, double& history,
                                   double& damage);

/// Largest principal value of a symmetric stress [Pa]; in 2D the largest in-plane one (see
/// damage_law.cpp for why the out-of-plane stress of plane strain never decides a tensile failure).
template <int D>
double largest_principal_stress(const Mat<D>& stress);

/// The undamaged elastic response that `degradation` acts on: the neo-Hookean model's Cauchy
/// stress [Pa] and energy ψ(F) [J/m³], or for Degradation::hencky_spectral the Hencky energy
/// ψ⁺ + ψ⁻ with the same bulk and shear moduli and its Cauchy stress σ⁺ + σ⁻. For the latter,
/// `split` (when given) receives the split, so that degrade_hencky need not compute it again.
template <int D>
void elastic_stress_and_energy(const NeoHookean& model, const Mat<D>& F, Degradation degradation,
                               Mat<D>& stress, double& psi, TensileSplit<D>* split = nullptr);

/// Degraded Cauchy stress [Pa] from the trial stress σ̄ and damage d: tensile principal stresses
/// scaled by (1 − d), compressive ones kept, same eigenvectors ([HH17] eq. (26)-(27)); or σ = (1 −
/// d) σ̄
/// ([XLS21] eq. (7)).
template <int D>
Mat<D> degrade_stress(const Mat<D>& trial_stress, double damage, Degradation degradation);

/// The energy per reference volume that damage acts on, ψ_t [J/m³]: the stored (recoverable)
/// energy is ψ(F) − d ψ_t and the damage dissipation of a step is Δd ψ_t.
///  * isotropic: ψ_t = ψ(F), since σ = (1 − d) σ̄ derives from (1 − d) ψ;
///  * tensile spectral: ψ_t = ½ Σ_{τ_i > 0} τ_i ln λ_i, with τ_i the principal Kirchhoff stresses
///  and
///    λ_i the principal stretches (b = F Fᵀ, coaxial with τ for an isotropic material). In 2D the
///    out-of-plane direction has λ₃ = 1 and adds nothing.
/// Why this is the secant dissipation: see damage_law.cpp; for uniaxial small strain it integrates
/// to ∫ ψ_t dd = G_f / l_ch per unit volume, i.e. G_f per unit area of a crack band of width l_ch.
template <int D>
double degradable_energy(const NeoHookean& model, const Mat<D>& F, Degradation degradation);

/// Degraded stress and degradable energy of a damaged particle from one spectral decomposition.
template <int D>
struct DegradedState {
  Mat<D> stress;            ///< degraded Cauchy stress [Pa]
  double degradable = 0.0;  ///< ψ_t [J/m³], not yet bounded by ψ
};

/// degrade_stress and degradable_energy together, with one eigen-solve: the trial stress of an
/// isotropic material (elastic part plus an isotropic thermal pressure) is coaxial with b = F Fᵀ,
/// so the eigenvectors n_i of b serve both: σ = σ̄ − d Σ_{σ̄_i > 0} σ̄_i n_i ⊗ n_i with σ̄_i = n_i·σ̄
/// n_i
/// ([HH17] eq. (26)-(27)), and ψ_t = ½ Σ_{τ_i > 0} τ_i ln λ_i. `psi` = ψ(F) [J/m³] (isotropic: ψ_t
/// = ψ).
template <int D>
DegradedState<D> degrade_with_energy(const NeoHookean& model, const Mat<D>& F,
                                     const Mat<D>& trial_stress, double damage,
                                     Degradation degradation, double psi);

/// Degradation::hencky_spectral from the split of F: σ = σ⁻ + (1 − d) σ⁺ plus `thermal_stress`
/// (the isotropic rest of the trial stress) scaled by (1 − d) only in expansion (J > 1), and
/// ψ_t = ψ⁺.
template <int D>
DegradedState<D> degrade_hencky(const TensileSplit<D>& split, const Mat<D>& thermal_stress,
                                double J, double damage);

/// Median of the Weibull strength of a particle of volume V [m³]: σ̄_f (V̄ / V)^{1/m} ([HH17] eq.
/// (25) with ℛ = ½). In 2D `volume` is an area and is multiplied by the thickness.
double weibull_median_strength(double volume, const WeibullStrength& weibull, int dimension);

/// Weibull strength per particle [Pa] ([HH17] eq. (25)): σ_f = σ̄_f (V̄/V · ln ℛ / ln ½)^{1/m}, ℛ
/// uniform in (0, 1) from std::mt19937_64 seeded with `weibull.seed`, drawn in particle order (so a
/// scene and a seed give the same strengths on every platform). `volumes` are the particles'
/// volumes [m³], or areas [m²] in 2D, which are multiplied by `weibull.thickness`.
std::vector<double> weibull_strengths(const std::vector<double>& volumes,
                                      const WeibullStrength& weibull, int dimension);

}  // namespace fragmpm::mpm
