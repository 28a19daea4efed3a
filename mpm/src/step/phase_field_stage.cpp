// The phase-field stage ([KT19] §4.2-4.3, Alg. 1): at the start of a step, with the history field
// H the last constitutive update left on the particles, assemble the nodal system of [KT19] eq.
// (56)-(57) by particle quadrature, solve it with conjugate gradients, and interpolate d back to
// the particles (eq. (53)); the mechanics of the step then degrade with g(d) (eq. (15)) in the
// constitutive update. One unknown per node and body: each body has its own field (eq. (28)).
//
// With γ = 0, eq. (47) multiplied by G_c/(4 l₀) is, for every weight q,
//   ∫ [(G_c/(4 l₀) + (1 − k_f) H) c q + G_c l₀ ∇c·∇q] dV = ∫ G_c/(4 l₀) q dV,
// so K_IJ = Σ_p V_p [(G_c/(4 l₀) + (1 − k_f) H_p) S̄_Ip S̄_Jp + G_c l₀ ∇S̄_Ip·∇S̄_Jp] and
// f_I = Σ_p V_p G_c/(4 l₀) S̄_Ip (eq. (57), (52)). The unknown is the paper's c = 1 − d, not d: the
// history of an open crack grows without bound (H/(G_c/(4 l₀)) reaches 10⁴-10⁸), and in d the
// right-hand side (1 − k_f) H would grow with it, so that the relative residual 10⁻⁶ of the
// conjugate gradients would be met while the field away from the crack is still wrong. In c the
// right-hand side is the same bounded G_c/(4 l₀) everywhere and H only stiffens the diagonal. The
// integrals are taken over the reference configuration (V_p = V₀, gradients Fᵀ∇S̄), where the
// history field and the stored energies of the constitutive update live (energies per reference
// volume): at small strain this is the paper's form, and a crack band that opens keeps its energy
#include <algorithm>

#include "step/phase_field_parts.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D, ShapeFunctionKind Kind>
void solve_phase_field(StepState<D>& state) {
  PhaseFieldState<D>& pf = *state.phase_field;
  auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  auto is_phase_field = [&](std::int64_t p) { return has_phase_field(state, p); };

  // Without any history the solution is d = 0 (the right-hand side vanishes): no system to solve.
  double largest_history = 0.0;
#pragma omp parallel for reduction(max : largest_history) schedule(static)
  for (std::int64_t p = 0; p < n; ++p)
    if (is_phase_field(p)) largest_history = std::max(largest_history, P.damage_history[p]);
  if (!(largest_history > 0.0)) {
    reset_array(pf.degradation_drop, P.size(), 0.0);
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < n; ++p)
      if (is_phase_field(p)) {
        const double k_f = pf.residual_stiffness[static_cast<std::size_t>(P.material[p])];
        pf.degradation_drop[static_cast<std::size_t>(p)] =
            phase_field_degradation(P.damage[p], k_f) - phase_field_degradation(0.0, k_f);
        P.damage[p] = 0.0;
      }
    state.totals.fracture_energy = 0.0;
    pf.iterations = 0;
    pf.residual = 0.0;
    pf.last = PhaseFieldWarmStart<D>{};
    return;
  }

  // The parts (phase_field_parts.hpp): unknowns, system, solve, and d back at the particles.
  number_phase_field_unknowns<D, Kind>(state);
  assemble_phase_field_system<D, Kind>(state);
  solve_phase_field_system<D>(state);
  interpolate_phase_field<D, Kind>(state);
}

#define FRAGMPM_INSTANTIATE(D)                                                  \
  template void solve_phase_field<D, ShapeFunctionKind::linear>(StepState<D>&); \
  template void solve_phase_field<D, ShapeFunctionKind::ugimp>(StepState<D>&);  \
  template void solve_phase_field<D, ShapeFunctionKind::cpdi>(StepState<D>&);   \
  template void solve_phase_field<D, ShapeFunctionKind::bspline2>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
