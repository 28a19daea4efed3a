#pragma once
// Thermo-mechanical coupling of one material point ([XLS21] §2.1-2.3): thermal stress, elastic
// structural heating, damage heating, and the explicit thermal stability limit. The nodal heat
// transfer that uses these lives in mpm/src/step/thermal_stage.cpp.
//
// Free energy per reference volume ([XLS21] eq. (1)-(5), (16)):
//   ρ₀ψ = (1 − d)(U(J) + W(b̄)) − 3(1 − d) α (θ − θ₀) U′(J) + ρ₀ c[(θ − θ₀) − θ ln(θ/θ₀)],
//   U = K/2 (ln J)²,  U′ = K ln J / J,  U″ = K (1 − ln J) / J².
#include <cmath>

#include "fragmpm/mpm/damage_law.hpp"
#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// U′(J) = K ln J / J [Pa], the derivative of the volumetric energy U = K/2 (ln J)² ([XLS21] eq.
/// (16)).
inline double volumetric_energy_slope(double bulk_modulus, double J) {
  return bulk_modulus * std::log(J) / J;
}

/// Thermal part of the Kirchhoff stress, a pressure times I: τ_θ = J ∂(ρ₀M)/∂J = −3αK(θ − θ₀)(1 −
/// ln J)/J
/// ([XLS21] eq. (3), (6); docs/design.md). Undamaged; damage degrades it together with the rest of
/// the stress. [Pa]
inline double thermal_kirchhoff_pressure(double bulk_modulus, double expansion, double temperature,
                                         double reference_temperature, double J) {
  return -3.0 * expansion * bulk_modulus * (temperature - reference_temperature) *
         (1.0 - std::log(J)) / J;
}

/// Thermal part of the Cauchy stress σ_θ = τ_θ / J (in-plane block in 2D) [Pa].
template <int D>
Mat<D> thermal_cauchy_stress(double bulk_modulus, double expansion, double temperature,
                             double reference_temperature, double J) {
  return (thermal_kirchhoff_pressure(bulk_modulus, expansion, temperature, reference_temperature,
                                     J) /
          J) *
         Mat<D>::Identity();
}

/// Fraction of the volumetric coupling energy M that damage d leaves: (1 − d) for isotropic
/// degradation ([XLS21] eq. (5)); with tensile-only degradation ([HH17] eq. (26)-(27)) a compressed
/// particle (J < 1) keeps its volumetric response, so its coupling is undegraded; so does the
/// volumetric-deviatoric split ([AMM09]), which degrades U(J) only in expansion.
inline double coupling_fraction(double damage, Degradation degradation, double J) {
  if (degradation != Degradation::isotropic && J < 1.0) return 1.0;
  return 1.0 - damage;
}

/// Temperature ratio θ(J₁)/θ(J₀) of an adiabatic elastic volume change J₀ → J₁ at fixed damage.
/// [XLS21] eq. (43) without conduction and damage growth reads ρ₀ c θ̇ = −ρ₀ H_e with
/// ρ₀ H_e = 3 α θ (1 − d) U″(J) J̇ (eq. (39)), i.e. d(ln θ)/dt = −3α(1 − d)/(ρ₀c) · d(U′(J))/dt, so
///   θ₁/θ₀ = exp(−3 α f (U′(J₁) − U′(J₀)) / (ρ₀ c)),  f = coupling_fraction.
/// Integrating this exactly (instead of an explicit θⁿ U″ ΔJ) makes a compress–release cycle return
/// to its starting temperature to round-off, as the reversible thermoelastic process must.
/// `density0` ρ₀ [kg/m³], `specific_heat` c [J/(kg K)].
inline double adiabatic_temperature_ratio(double bulk_modulus, double expansion, double density0,
                                          double specific_heat, double fraction, double J_from,
                                          double J_to) {
  const double change =
      volumetric_energy_slope(bulk_modulus, J_to) - volumetric_energy_slope(bulk_modulus, J_from);
  return std::exp(-3.0 * expansion * fraction * change / (density0 * specific_heat));
}

/// Heat released per reference volume by a damage increment Δd ([XLS21] eq. (28), (40), (43)):
/// ρ₀(D_int − H_in) Δt = [ψ̄ − 3α(θ − θ₀)U′ + 3αθU′] Δd = (ψ̄ + 3 α θ₀ U′(J)) Δd,
/// with ψ̄ the degradable stored energy (the same ψ_t whose release the mechanics books as
/// `dissipated`, so the heat equals the recorded damage dissipation plus the coupling term). [J/m³]
inline double damage_heat_density(double degradable_energy, double bulk_modulus, double expansion,
                                  double reference_temperature, double J, double damage_increment) {
  return (degradable_energy +
          3.0 * expansion * reference_temperature * volumetric_energy_slope(bulk_modulus, J)) *
         damage_increment;
}

/// Explicit conduction limit Δt ≤ C ρ c h² / (2 D κ) (docs/design.md), smallest over the particles
/// with ρ = m / (V₀ J) the current density. Infinite when the thermal module is off or nothing
/// conducts. `courant` C: 1 gives the stability limit itself. [s]
template <int D>
double thermal_stable_time_step(const Problem<D>& problem, const Particles<D>& particles,
                                double courant);

/// Heat content relative to the reference temperatures, Σ m_p c_p (θ_p − θ₀) [J per unit thickness
/// in 2D]; 0 when the module is off.
template <int D>
double thermal_energy(const Problem<D>& problem, const Particles<D>& particles);

}  // namespace fragmpm::mpm
