// P2G ([XLS21] eq. (47)-(49)): m_i = Σ S̄ m_p, p_i = Σ S̄ m_p v_p, f_i = Σ S̄ (m_p g + f_p) − Σ V_p
// σ_p ∇S̄ (f_p: traction loads and penalty walls, [XLS21] eq. (87)), into the particle's field at
// each node as the field map says ([HH17] Alg. 2), with the contact sums at the nodes that can hold
// two fields. APIC ([JSS15]) adds the momentum of the particle's affine field at the node, m_p S̄_ip
// C_p (x_i − x_p): a rigid or affine motion then reaches the grid exactly at every node, partly
// filled or not, since Σ S̄ (x_i − x_p) = 0 keeps the total momentum and linear completeness gives
// m_i v_i = Σ S̄ m_p v(x_i).
#include <algorithm>

#include "step/particle_loops.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D, ShapeFunctionKind Kind, bool Partitioned, bool Affine>
void scatter_to_grid(StepState<D>& state) {
  const auto& P = state.problem.particles;
  NodeFields<D>& N = state.nodes;
  ContactSums<D>& sums = state.contact;
  const PartitionState<D>& part = state.partition;
  const Vec<D> gravity = state.problem.gravity;
  const bool loaded = !state.load_force.empty();
  const bool penalty = state.penalty_walls;
  const bool by_bodies = state.plan.by_bodies;
  const bool gap_test = state.plan.gap_test;
  const bool wall_gap_test = state.plan.wall_gap_test;
  const bool area_needed = state.plan.needs_contact_area;
  scatter_particles<D, Kind, Affine>(state, [&](std::int64_t p, const Stencil<D>& s) {
    const double volume = P.volume0[p] * P.F[p].determinant();
    const Mat<D> volume_stress = volume * P.stress[p];
    const Vec<D> momentum = P.mass[p] * P.v[p];
    const Vec<D> external = P.mass[p] * gravity + (loaded ? state.load_force[p] : Vec<D>::Zero()) +
                            (penalty ? state.penalty_force[p] : Vec<D>::Zero());
    for (int e = 0; e < s.count; ++e) {
      const std::size_t i = static_cast<std::size_t>(s.node[e]);
      const int f = field_at<D, Partitioned>(state, p, e);
      N.mass[f][i] += s.weight[e] * P.mass[p];
      if (wall_gap_test) N.position[f][i] += s.weight[e] * P.mass[p] * P.x[p];
      if constexpr (Affine)
        N.momentum[f][i] += s.weight[e] * (momentum + P.mass[p] * (P.affine[p] * s.offset[e]));
      else
        N.momentum[f][i] += s.weight[e] * momentum;
      N.force[f][i] += s.weight[e] * external - volume_stress * s.gradient[e];
      if constexpr (Partitioned) {
        // Only a node with a nodal damage gradient can have two fields and needs the contact sums.
        if (!by_bodies && !(part.node_gradient[i].squaredNorm() > 0.0)) continue;
        sums.mass_gradient[f][i] += P.mass[p] * s.gradient[e];
        const double dhat = by_bodies ? 0.0 : part.particle_dhat[p];
        sums.dhat[f][i] += s.weight[e] * P.mass[p] * dhat;
        if (s.weight[e] > 0.0) sums.dhat_max[i] = std::max(sums.dhat_max[i], dhat);
        if (gap_test) sums.position[f][i] += s.weight[e] * P.mass[p] * P.x[p];
        if (area_needed) sums.volume_gradient[f][i] += volume * s.gradient[e];
      }
    }
  });
}

#define FRAGMPM_INSTANTIATE_KIND(D, K)                                                 \
  template void scatter_to_grid<D, ShapeFunctionKind::K, false, false>(StepState<D>&); \
  template void scatter_to_grid<D, ShapeFunctionKind::K, true, false>(StepState<D>&);  \
  template void scatter_to_grid<D, ShapeFunctionKind::K, false, true>(StepState<D>&);  \
  template void scatter_to_grid<D, ShapeFunctionKind::K, true, true>(StepState<D>&);
#define FRAGMPM_INSTANTIATE(D)        \
  FRAGMPM_INSTANTIATE_KIND(D, linear) \
  FRAGMPM_INSTANTIATE_KIND(D, ugimp)  \
  FRAGMPM_INSTANTIATE_KIND(D, cpdi)   \
  FRAGMPM_INSTANTIATE_KIND(D, bspline2)
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE
#undef FRAGMPM_INSTANTIATE_KIND

}  // namespace fragmpm::mpm
