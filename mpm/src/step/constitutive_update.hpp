#pragma once
// The constitutive update of one particle, the same at initialisation and at the end of every step:
// trial stress σ̄ from F (neo-Hookean plus the thermal pressure, [XLS21] eq. (3)), the damage law on
// σ̄, and the degraded stress with the stored energy ψ(F) − d ψ_t ([HH17] eq. (26)-(27) or
// [XLS21] eq. (7)). ψ_t is the energy the degradation acts on; raising d by Δd at fixed F releases
// Δd ψ_t (the secant dissipation, see damage_law.cpp).
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#include "fragmpm/mpm/crushed_flow.hpp"
#include "fragmpm/mpm/damage_law.hpp"
#include "fragmpm/mpm/phase_field.hpp"
#include "step/step_state.hpp"

namespace fragmpm::mpm {

struct ConstitutiveResult {
  double stored = 0.0;      ///< recoverable energy per reference volume [J/m³]
  double dissipated = 0.0;  ///< released by this update's damage increment [J/m³]
  double flowed = 0.0;      ///< released by the frictional flow of failed material [J/m³]
  /// Phase field: what this step's crack growth took from the history field beyond the tensile
  /// energy it released, (g_old − g_new)(H − ψ⁺) (docs/design.md §2.5, "Energy") [J/m³].
  double history_excess = 0.0;
};

/// The elastic deformation F_e = F F_p⁻¹ of particle p: F itself unless failed material can flow.
template <int D>
inline Mat<D> elastic_deformation(const StepState<D>& state, std::int64_t p) {
  const auto& P = state.problem.particles;
  if (P.plastic_inverse.empty()) return P.F[p];
  return P.F[p] * P.plastic_inverse[p];
}

/// The trial (undamaged) stress σ̄ of particle p from F and, with the thermal module, θ. The
/// elastic law is the neo-Hookean, or the Hencky energy of a material degraded by its split.
template <int D, bool Thermal>
inline Mat<D> trial_stress(const StepState<D>& state, std::int64_t p, double& psi,
                           TensileSplit<D>* split = nullptr) {
  const auto& P = state.problem.particles;
  const int material = P.material[p];
  Mat<D> trial;
  elastic_stress_and_energy<D>(
      state.models[static_cast<std::size_t>(material)], elastic_deformation(state, p),
      state.problem.materials[static_cast<std::size_t>(material)].degradation, trial, psi, split);
  if constexpr (Thermal) trial += state.thermal->stress(material, P.F[p], P.temperature[p]);
  return trial;
}

/// A particle of a phase-field material: the spectral split of its (Hencky) elastic energy
/// ([KT19] eq. (14)), the history field H = max over time of ψ⁺ (the Kuhn–Tucker conditions of
/// [KT19] §3.1, Alg. 1) when AdvanceDamage, and the stress g(d) σ⁺ + σ⁻ (eq. (15)-(16)) with the d
/// of this step's phase-field solve. Nothing is booked as dissipation: the energy the phase field
/// takes is its crack energy Ψ_f. The thermal module is refused with phase-field materials.
template <int D, bool AdvanceDamage>
inline ConstitutiveResult update_phase_field_particle(StepState<D>& state, std::int64_t p) {
  auto& P = state.problem.particles;
  const std::size_t material = static_cast<std::size_t>(P.material[p]);
  const NeoHookean& model = state.models[material];
  const double lambda = model.bulk_modulus - 2.0 * model.shear_modulus / 3.0;
  const TensileSplit<D> split = hencky_tensile_split<D>(lambda, model.shear_modulus, P.F[p]);
  double history_excess = 0.0;
  if constexpr (AdvanceDamage) {
    // The step's solve minimised g(d) H + the crack density with the history H of the last update,
    // so its crack energy grew by Σ V₀ (g_old − g_new) H less a non-negative quadratic term
    // (design.md §2.5), while the degradation releases only (g_old − g_new) ψ⁺ of strain energy.
    const std::vector<double>& drop = state.phase_field->degradation_drop;
    if (static_cast<std::size_t>(p) < drop.size())
      history_excess =
          drop[static_cast<std::size_t>(p)] * (P.damage_history[p] - split.tensile_energy);
    P.damage_history[p] = std::max(P.damage_history[p], split.tensile_energy);
  }
  const double g =
      phase_field_degradation(P.damage[p], state.phase_field->residual_stiffness[material]);
  P.stress[p] = g * split.tensile_stress + split.compressive_stress;
  return {g * split.tensile_energy + split.compressive_energy, 0.0, 0.0, history_excess};
}

/// AdvanceDamage: evaluate the damage law (the step); false keeps d (initial state, restart).
/// `equivalent_stress`: when finite, the σ₁ that drives the damage law in place of the trial
/// stress's own largest principal value (the nonlocal average, nonlocal_damage.cpp).
template <int D, bool Thermal, bool AdvanceDamage>
inline ConstitutiveResult update_constitutive(
    StepState<D>& state, std::int64_t p, double dt,
    double equivalent_stress = std::numeric_limits<double>::quiet_NaN()) {
  auto& P = state.problem.particles;
  const int material = P.material[p];
  const char law = state.material_damages[static_cast<std::size_t>(material)];
  if (law == material_phase_field) return update_phase_field_particle<D, AdvanceDamage>(state, p);
  const NeoHookean& model = state.models[static_cast<std::size_t>(material)];
  double psi;
  TensileSplit<D> split;  // filled only for a Hencky-split material, reused by its degradation
  Mat<D> trial = trial_stress<D, Thermal>(state, p, psi, &split);
  if (!law) {
    P.stress[p] = trial;
    return {psi, 0.0};
  }
  const MaterialSpec& spec = state.problem.materials[static_cast<std::size_t>(material)];
  const double damage_before = P.damage[p];
  if constexpr (AdvanceDamage) {
    const double l_ch = characteristic_length<D>(spec, P.volume0[p], state.grid.cell_size);
    if (std::isfinite(equivalent_stress))
      update_damage_from_equivalent(spec.damage, equivalent_stress, P.strength[p], l_ch, dt,
                                    P.damage_history[p], P.damage[p]);
    else
      update_damage<D>(spec.damage, trial, P.strength[p], l_ch, dt, P.damage_history[p],
                       P.damage[p]);
  }
  const double d = P.damage[p];
  if (d <= 0.0) {
    P.stress[p] = trial;
    // An intact particle's ψ_t is not needed: its first damage increment is booked at the end
    // state alone (below).
    return {psi, 0.0};
  }
  // The damage increment releases ψ⁺ of the trial state; a failed particle's flow then dissipates
  // what crushed_flow.hpp derives, and the stress is the returned state's.
  const double trial_psi = psi, trial_tensile = split.tensile_energy;
  double flowed = 0.0;
  if constexpr (AdvanceDamage) {
    const double sine = state.crushed_sine[static_cast<std::size_t>(material)];
    if (sine > 0.0 && d >= 1.0) {
      const Mat<D> elastic_F = elastic_deformation(state, p);
      const double lambda = model.bulk_modulus - 2.0 * model.shear_modulus / 3.0;
      const CrushedFlowReturn<D> flow =
          crushed_flow_return<D>(elastic_F, lambda, model.shear_modulus, sine);
      if (flow.flowed) {
        P.plastic_inverse[p] = P.F[p].inverse() * flow.correction * elastic_F;
        // The CPDI domain follows the elastic deformation, not the flow: sheared with F, a
        // flowing particle's domain became a sliver whose area the cell limit cut by the square
        // of its stretch, and whose shape-function gradients (∝ 1/width) grew until one step's
        // velocity gradient inverted it (fine Brazilian disk, 17.9 µs: F₁₁ = 22, domain 74 × 5 µm
        // with edges 7° apart). Flow without dilatancy keeps the volume, so the domain's area
        // stays J A₀.
        if (state.problem.grid.shape_function == ShapeFunctionKind::cpdi)
          P.domain[p] = flow.correction * P.domain[p];
        trial = trial_stress<D, Thermal>(state, p, psi, &split);
        // The step the particle failed in releases the shear energy stored beyond the bound;
        // later steps book the plastic work (crushed_flow.hpp).
        flowed = damage_before < 1.0 ? flow.released : flow.plastic_work;
        if constexpr (Thermal) state.flow_heat[static_cast<std::size_t>(p)] = flowed;
      }
    }
  }
  const DegradedState<D> degraded =
      spec.degradation == Degradation::hencky_spectral
          ? degrade_hencky<D>(split, trial - split.tensile_stress - split.compressive_stress,
                              P.F[p].determinant(), d)
          : degrade_with_energy<D>(model, P.F[p], trial, d, spec.degradation, psi);
  // ½ Σ τᵢ ln λᵢ is the exact released energy only at small strain; at large stretch it can exceed
  // ψ itself, so it is bounded by ψ: damage never stores negative energy. (The potentials of the
  // volumetric-deviatoric and Hencky splits release at most ψ; the bound never acts on them.)
  const double degradable = std::clamp(degraded.degradable, 0.0, psi);
  P.stress[p] = degraded.stress;
  // The dissipation of the step is ∫ ψ_t dd over it ([XLS21] eq. (6): Y = ψ_t drives ḋ). Taken
  // at the step's end, Δd ψ_t(end), it exceeds the integral by ½ Δd Δψ_t wherever the particle
  // softens while it stretches, and the balance showed the excess as energy created. The
  // trapezoid ½ Δd (ψ_t(start) + ψ_t(end)) is the integral to second order, and it makes the
  // energy of the step, (1 − d_start) Δψ_t − ½ Δd Δψ_t, the quadratic form of the tangent
  // dσ = (1 − d) C dε − σ̄⁺ dd that the explicit step integrates, instead of the secant's
  // (docs/design.md §2.4, "Softening"). The first increment of a particle that was intact is booked
  // at the end state (ψ_t is not kept for intact particles; the increment is small there).
  // The step a failed particle starts to flow keeps its own release (crushed_flow.hpp).
  const std::size_t index = static_cast<std::size_t>(p);
  double released = flowed > 0.0 ? std::clamp(trial_tensile, 0.0, trial_psi) : degradable;
  if constexpr (AdvanceDamage)
    if (flowed == 0.0 && damage_before > 0.0 && d > damage_before)
      released = 0.5 * (state.release_before[index] + degradable);
  state.release_before[index] = degradable;
  if constexpr (Thermal) state.degradable[index] = flowed > 0.0 ? degradable : released;
  return {psi - d * degradable, (d - damage_before) * released, flowed};
}

}  // namespace fragmpm::mpm
