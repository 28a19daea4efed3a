// Step 6 of the phase-field stage: d, its gradient and the crack energy at the particles.
#include <algorithm>

#include "step/particle_loops.hpp"
#include "step/phase_field_parts.hpp"

namespace fragmpm::mpm {

template <int D, ShapeFunctionKind Kind>
void interpolate_phase_field(StepState<D>& state) {
  PhaseFieldState<D>& pf = *state.phase_field;
  auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  auto is_phase_field = [&](std::int64_t p) { return has_phase_field(state, p); };
  auto field_of = [&](std::int64_t p) { return field_of_body(pf, P.body[p]); };
  constexpr int K = PhaseFieldState<D>::slots;
  const GridIndex<D>& grid = state.grid;

  // 6. d = 1 − c and ∇d at the particles (eq. (53)-(54)) and the crack energy of the discrete
  //    field, Ψ_f = Σ V₀ G_c (d²/(4 l₀) + l₀ |∇d|²) (eq. (3)-(4)), plus G_c l₀³ χᵀ Γ χ with the
  //    anisotropy. The interpolant may stray outside [0, 1] by the consistent mass's undershoot;
  //    the particles keep d clamped to it.
  double crack_energy = 0.0;
  const Eigen::VectorXd& c = pf.solution;
  size_array(pf.degradation_drop, P.size());
#pragma omp parallel reduction(+ : crack_energy)
  {
    Stencil<D> s;
    std::array<Eigen::Vector3d, Stencil<D>::capacity> chi;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      pf.degradation_drop[static_cast<std::size_t>(p)] = 0.0;
      if (!is_phase_field(p)) continue;
      fill_stencil<D, Kind>(P, p, grid, s);
      const std::size_t material = static_cast<std::size_t>(P.material[p]);
      const bool fourth_order = has_fourth_order<D, Kind>(pf, material);
      if constexpr (D == 2)
        if (fourth_order) bspline2_reference_curvatures(P.x[p], P.F[p], grid, chi);
      double value = 0.0;
      Vec<D> gradient = Vec<D>::Zero();
      Eigen::Vector3d curvature = Eigen::Vector3d::Zero();
      for (int e = 0; e < s.count; ++e) {
        if (empty_entry(s, e)) continue;
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        const double nodal =
            1.0 - c[pf.node_unknown[i * K + static_cast<std::size_t>(slot_of(pf, i, field_of(p)))]];
        value += s.weight[e] * nodal;
        gradient += nodal * s.gradient[e];
        if (fourth_order) curvature += nodal * chi[e];
      }
      gradient = P.F[p].transpose() * gradient;
      const double l0 = pf.length_scale[material];
      crack_energy += P.volume0[p] * pf.fracture_energy[material] *
                      (value * value / (4.0 * l0) + l0 * gradient.squaredNorm());
      if (fourth_order)  // G_c l₀³ χᵀ Γ χ ([KT19] eq. (4))
        crack_energy += P.volume0[p] * curvature.dot(pf.fourth_order[material] * curvature);
      const double damage = std::clamp(value, 0.0, 1.0);
      pf.degradation_drop[static_cast<std::size_t>(p)] =
          phase_field_degradation(P.damage[p], pf.residual_stiffness[material]) -
          phase_field_degradation(damage, pf.residual_stiffness[material]);
      P.damage[p] = damage;
    }
  }
  state.totals.fracture_energy = crack_energy;
}

#define FRAGMPM_INSTANTIATE(D)                                                        \
  template void interpolate_phase_field<D, ShapeFunctionKind::linear>(StepState<D>&); \
  template void interpolate_phase_field<D, ShapeFunctionKind::ugimp>(StepState<D>&);  \
  template void interpolate_phase_field<D, ShapeFunctionKind::cpdi>(StepState<D>&);   \
  template void interpolate_phase_field<D, ShapeFunctionKind::bspline2>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
