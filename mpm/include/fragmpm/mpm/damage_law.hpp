#pragma once
// Damage laws (DESIGN §4 "Damage laws"), chosen per material. Plain structs in a std::variant: the
// per-particle dispatch is a jump table, not a virtual call.
#include <variant>

namespace fragmpm::mpm {

/// No damage: the material stays elastic.
struct NoDamage {};

/// Rankine with mesh-regularised linear softening (000 eq. 19-21; 001 eq. 23). The strength σ_f is
/// per particle (Particles::strength), so a Weibull field can replace the uniform value.
struct RankineSoftening {
  double fracture_energy = 0.0;  ///< G_f [J/m²]
  double youngs_modulus = 0.0;   ///< E [Pa], for the brittleness H̄ = σ_f² / (2 E G_f) (eq. 21)
};

/// Time to failure (001 eq. 24): once the largest principal stress reaches σ_f, d grows by Δt/τ
/// per step with τ = l_ch / c_f (the paper's "τ = c_f/ℓ" is a transit time, so ℓ/c_f).
struct TimeToFailure {
  double crack_speed = 0.0;  ///< c_f [m/s]
};

using DamageLaw = std::variant<NoDamage, RankineSoftening, TimeToFailure>;

/// How damage degrades the stress.
enum class Degradation {
  tensile_spectral,  ///< only tensile principal stresses scale by (1 − d) (001 eq. 26-27)
  isotropic,         ///< σ = (1 − d) σ^E (000 eq. 7)
};

/// Weibull strength per particle (001 eq. 25): σ_f / σ̄_f = (V̄/V · ln ℛ / ln ½)^{1/m}.
struct WeibullStrength {
  double reference_strength = 0.0;  ///< σ̄_f [Pa]
  double reference_volume = 0.0;    ///< V̄ [m³]
  double modulus = 0.0;             ///< m
  double thickness = 0.0;           ///< out-of-plane thickness for V in 2D [m]
  unsigned long long seed = 0;
};

}  // namespace fragmpm::mpm
