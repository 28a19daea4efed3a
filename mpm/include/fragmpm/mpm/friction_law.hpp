#pragma once
// Friction laws for the momentum-exchange contact of [NBS18] §2.6: each law gives the sliding
// traction S_slide that the contact can carry, from the normal momentum change d_n, the stick
// tangential momentum change d_t, the reduced mass and the contact area. Laws are plain structs
// held in a std::variant, so the per-node dispatch is a jump table, not a virtual call
// (docs/design.md).
#include <variant>

namespace fragmpm::mpm {

/// S = μ N ([NBS18] §2.7, eq. (20)).
struct CoulombFriction {
  double coefficient = 0.0;  ///< μ
};

/// μ = μ₀ + k |Δv′| with Δv′ the slip velocity left after the step ([NBS18] §2.8, eq. (22)-(23)).
struct VelocityDependentFriction {
  double coefficient = 0.0;  ///< μ₀
  double slope = 0.0;        ///< k [s/m]
};

/// S = S_a + μ N; separated surfaces stay stuck until the elliptical criterion of eq. (25) breaks
/// them
/// ([NBS18] §2.9, eq. (24)-(25)). Needs the contact area (eq. (11)).
struct AdhesiveFriction {
  double coefficient = 0.0;       ///< μ
  double shear_strength = 0.0;    ///< S_a [Pa]
  double tensile_strength = 0.0;  ///< N_a [Pa]; 0 = no tensile adhesion
};

/// Smooth static → dynamic transition μ(|Δv′|) = (μ_s v½ + μ_d |Δv′|) / (v½ + |Δv′|), solved for
/// the final slip velocity ([NBS18] eq. (42)-(43)).
struct SmoothStaticDynamicFriction {
  double static_coefficient = 0.0;   ///< μ_s
  double dynamic_coefficient = 0.0;  ///< μ_d
  double half_velocity = 0.0;        ///< v½ [m/s]
};

/// μ = μ₀ ⟨θ_dam − θ⟩² / (θ_dam − θ_ref)² ([XLS21] eq. (15), ⟨·⟩ the Macaulay bracket) with θ the
/// hotter side's temperature: μ = μ₀ at θ_ref, friction vanishes at and above θ_dam.
struct ThermalSofteningFriction {
  double coefficient = 0.0;            ///< μ₀ at θ_ref
  double reference_temperature = 0.0;  ///< θ_ref [K]
  double damage_temperature = 0.0;     ///< θ_dam [K]
};

using FrictionLaw = std::variant<CoulombFriction, VelocityDependentFriction, AdhesiveFriction,
                                 SmoothStaticDynamicFriction, ThermalSofteningFriction>;

/// μ(|Δv′|) = μ₀ + k |Δv′| at slip speed `slip` [m/s] ([NBS18] §2.8).
inline double friction_coefficient(const VelocityDependentFriction& law, double slip) {
  return law.coefficient + law.slope * slip;
}

/// μ(|Δv′|) = (μ_s v½ + μ_d |Δv′|) / (v½ + |Δv′|) at slip speed `slip` [m/s] ([NBS18] eq. (42)).
/// v½ = 0 is the sharp static/dynamic law: μ_s at rest, μ_d once sliding.
inline double friction_coefficient(const SmoothStaticDynamicFriction& law, double slip) {
  const double denominator = law.half_velocity + slip;
  if (denominator <= 0.0) return law.static_coefficient;
  return (law.static_coefficient * law.half_velocity + law.dynamic_coefficient * slip) /
         denominator;
}

/// μ(θ) = μ₀ ⟨θ_dam − θ⟩² / (θ_dam − θ_ref)² at temperature θ [K] ([XLS21] eq. (15)).
inline double friction_coefficient(const ThermalSofteningFriction& law, double temperature) {
  const double span = law.damage_temperature - law.reference_temperature;
  const double remaining = law.damage_temperature - temperature;
  if (remaining <= 0.0) return 0.0;         // Macaulay bracket ⟨θ_dam − θ⟩
  if (span == 0.0) return law.coefficient;  // degenerate θ_dam = θ_ref: a step at θ_dam
  return law.coefficient * (remaining * remaining) / (span * span);
}

}  // namespace fragmpm::mpm
