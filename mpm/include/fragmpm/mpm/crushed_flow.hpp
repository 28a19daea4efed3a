#pragma once
// Failed material as a cohesionless frictional solid (docs/design.md "Crushed material").
//
// Under the Hencky spectral split a failed particle (d = 1) keeps ψ⁻, the energy of its compressed
// principal strains, shear between them included. That is right for a crack that closes, but a
// crushed zone of failed particles is a granular material: it can carry a shear stress only in
// proportion to its pressure. Without that bound the crushed zone under a platen holds principal
// stress differences of gigapascals between neighbours, which no frictional material carries.
//
// The bound is Mohr–Coulomb with friction angle φ and no cohesion: in 2D on the in-plane principal
// stresses, (σ_max − σ_min)/2 ≤ −sin φ (σ_max + σ_min)/2 [plane strain, the out-of-plane stress
// taken as the intermediate one]; in 3D the Drucker–Prager cone through Mohr–Coulomb's compression
// meridian, √(3 J₂) ≤ M p with M = 6 sin φ / (3 − sin φ) and p = −tr σ / 3 ([CH88]). Both are
// homogeneous of degree one in the stress, so the Kirchhoff stress τ = J σ serves.
//
// Flow is multiplicative, F = F_e F_p, with the elastic logarithmic strains ε_i = ln λ_i of
// b_e = F_e F_eᵀ. The plastic flow has no dilatancy and is deviatoric, coaxial with b_e: the return
// keeps the mean elastic strain m and scales the deviator, ε_i ← m + s (ε_i − m), with the largest
// s ∈ [0, 1] on or inside the surface. This is the exponential-map return of finite-strain
// plasticity in principal logarithmic strains ([Sim92]): the update
// F_e ← Σ_i exp(ε_i^new − ε_i) n_i ⊗ n_i · F_e is exact for any step size and keeps det F_e. In 2D
// the mean is in-plane: the out-of-plane elastic strain stays 0, as plane strain requires when
// the flow is in-plane.
//
// What flow_dissipation books. In steady flow it is the backward-Euler plastic work at the
// returned stress, τ^new : Δε^p = Σ_i τ_i^new (ε_i − ε_i^new), the discrete ∫ τ : d^p dt. The
// energy the return takes, ψ⁻(ε) − ψ⁻(ε^new), exceeds it by ½ Δε^p : C : Δε^p, and that excess is
// the second-order term of the trial step: update-stress-last works with the start-of-step stress,
// σ_n : Δε, while the trial state stores σ_n : Δε + ½ Δε : C : Δε. In an elastic particle that term
// stays in the strain energy and cancels the explicit step's kinetic error over a vibration;
// booking it as dissipation of a flowing one leaves that kinetic error in the balance. Measured on
// a free failed block in its longitudinal mode (test_solver.cpp, ν = 0, φ = 30°, one period):
// balance −0.9 % of E₀ booking τ^new : Δε^p, +24 % booking ψ⁻(ε) − ψ⁻(ε^new). The step a particle
// fails in is different: its trial state holds the shear energy it stored beyond the bound over
// many earlier steps, work the balance already counted, and the first return releases it; that step
// books the whole release, as a damage increment books Δd ψ⁺.
#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// The result of one return of a failed particle's elastic state.
template <int D>
struct CrushedFlowReturn {
  /// The factor that takes the trial elastic deformation to the returned one, F_e ← C F_e;
  /// identity when the particle does not flow.
  Mat<D> correction = Mat<D>::Identity();
  double deviator_scale = 1.0;  ///< s: the returned deviatoric elastic strain over the trial one
  /// τ^new : Δε^p, the plastic work of the return per reference volume [J/m³].
  double plastic_work = 0.0;
  /// ψ⁻(ε) − ψ⁻(ε^new), the energy per reference volume the return releases [J/m³].
  double released = 0.0;
  bool flowed = false;
};

/// The yield function f of a failed Hencky particle from its principal elastic logarithmic
/// strains (ε_1 … ε_D; in 2D the out-of-plane one is 0): the principal Kirchhoff stresses of ψ⁻,
/// τ_i = λ ⟨tr ε⟩₋ + 2μ ⟨ε_i⟩₋, in the criterion above. f ≤ 0 is admissible; f is in Pa.
template <int D>
double crushed_yield_function(const Vec<D>& log_strains, double lambda, double shear_modulus,
                              double sin_friction);

/// The return of a failed particle with elastic deformation `elastic_F` (λ, μ the Lamé constants
/// [Pa], sin φ of the friction angle φ): the largest deviator scale s ∈ [0, 1] with f ≤ 0, by
/// bisection on s (f(0) ≤ 0 always: a hydrostatic or stress-free state is admissible), to the
/// last bit. No flow when the trial state is admissible.
template <int D>
CrushedFlowReturn<D> crushed_flow_return(const Mat<D>& elastic_F, double lambda,
                                         double shear_modulus, double sin_friction);

}  // namespace fragmpm::mpm
