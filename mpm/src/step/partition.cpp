// The partition stages of a step ([HH17] §2.1-2.4, Alg. 1-2): the kernel damage field and its
// gradient at the particles, the nonlocal nodal gradient, the two sides of the d̂-band at each node,
// and the field map, which decides the field of every particle-node pair once for the whole step.
#include <algorithm>
#include <cmath>

#include "step/particle_loops.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

namespace {

/// Whether Alg. 2's sign test is meaningless for surface particle p at node i because p sits where
/// pre-existing surfaces meet. [HH17] §2.4 makes touching bodies separable by flagging their
/// boundary particles (d̂ = s = 1), so the kernel field D̄ is a band along every flagged face and
/// ∇D̄_p points from p's side into the band ([HH17] eq. (17)-(19)). At a node of a contact surface
/// whose band ends at a free face of one body (the billet corner under the overhanging platen), the
/// corner particle's ∇D̄_p points along the free face's normal, within a few degrees of the contact
/// plane, and ∇D̄_p · ∇D̄_i ([HH17] Alg. 2) is the noise of two almost perpendicular vectors: the
/// corner would join the other body's field and be dragged with it. Such a particle is instead put
/// on the side of the band it lies on, as Alg. 2 already does for particles with ∇D̄_p = 0: the band
/// particles whose gradients do decide (|cos| ≥ ambiguous_gradient_cosine) give the two sides'
/// centres c_0, c_1 (band_sides), and p joins the nearer one along c_1 − c_0, the local normal of
/// the band, which at the corner is not tilted by the free face's flags as ∇D̄_i is. It applies only
/// to faces that exist before any damage: p's d̂ is its surface flag (s_p = 1, d_p < D_cr) and no
/// particle with damage d ≥ D_min maps to the node. At a growing crack the tip particles' gradients
/// are also almost in the crack plane, but there the sign test is what [HH17] §2.2-2.3 validate
/// (applying the rule there stopped the notched-bar crack at 6 of 8 mm).
template <int D>
bool junction_of_surfaces(const StepState<D>& state, std::int64_t p, std::size_t node,
                          const Vec<D>& g, const Vec<D>& nodal) {
  const auto& P = state.problem.particles;
  const PartitionState<D>& part = state.partition;
  return P.surface[p] != 0 && P.damage[p] < state.problem.contact.critical_damage &&
         part.node_damage_max[node] < state.problem.contact.minimum_damage &&
         part.node_side_weight[0][node] > 0.0 && part.node_side_weight[1][node] > 0.0 &&
         !gradient_decides_field<D>(g, nodal) && nodal.squaredNorm() > 0.0;
}

/// [HH17] Alg. 2: field 0 when ∇D̄_p · ∇D̄_i ≥ 0, else field 1; a particle beyond the reach of any
/// damage (∇D̄_p = 0) joins the side of the node it lies on instead of always field 0, and a surface
/// particle at a junction of pre-existing surfaces the side of the band it lies on. With
/// partitioning by bodies the field is the body ([NBS18] §2.2, multimaterial contact).
template <int D>
int field_of(const StepState<D>& state, std::int64_t p, std::size_t node) {
  const auto& P = state.problem.particles;
  if (state.plan.by_bodies) return P.body[p] == 0 ? 0 : 1;
  const PartitionState<D>& part = state.partition;
  const Vec<D>& g = part.particle_gradient[p];
  const Vec<D>& nodal = part.node_gradient[node];
  if (g.squaredNorm() > 0.0) {
    if (!junction_of_surfaces(state, p, node, g, nodal)) return particle_field_at_node<D>(g, nodal);
    const Vec<D> c0 = part.node_side_moment[0][node] / part.node_side_weight[0][node];
    const Vec<D> c1 = part.node_side_moment[1][node] / part.node_side_weight[1][node];
    return (P.x[p] - 0.5 * (c0 + c1)).dot(c1 - c0) <= 0.0 ? 0 : 1;
  }
  if (nodal.squaredNorm() == 0.0) return 0;  // a node away from any damage: one field
  const Vec<D> offset =
      P.x[p] - state.grid.position(state.grid.global(static_cast<std::int64_t>(node)));
  return particle_field_at_node<D>(g, nodal, offset);
}

/// The two sides of the d̂-band at each node (for the junction rule): Σ S̄ d̂_p x_p and Σ S̄ d̂_p per
/// field over the band particles whose gradient decides their field there (Alg. 2's sign test).
template <int D, ShapeFunctionKind Kind>
void band_sides(StepState<D>& state) {
  PartitionState<D>& part = state.partition;
  const auto& P = state.problem.particles;
  auto in_band = [&](std::int64_t p) {
    return part.particle_dhat[p] > 0.0 && part.particle_gradient[p].squaredNorm() > 0.0;
  };
  scatter_particles_where<D, Kind>(state, in_band, [&](std::int64_t p, const Stencil<D>& s) {
    const double dhat = part.particle_dhat[p];
    const Vec<D>& g = part.particle_gradient[p];
    for (int e = 0; e < s.count; ++e) {
      const std::size_t i = static_cast<std::size_t>(s.node[e]);
      if (s.weight[e] <= 0.0 || !gradient_decides_field<D>(g, part.node_gradient[i])) continue;
      const int f = particle_field_at_node<D>(g, part.node_gradient[i]);
      part.node_side_weight[f][i] += s.weight[e] * dhat;
      part.node_side_moment[f][i] += (s.weight[e] * dhat) * P.x[p];
    }
  });
}

/// The nonlocal nodal damage-field gradient ([HH17] §2.2). Default: the principal direction of
/// Σ_p ∇D̄_p ⊗ ∇D̄_p over the particles mapping to the node, the n maximising Σ_p (n·∇D̄_p)², so the
/// opposite gradients on the two faces of a crack reinforce. Alternative: [HH17] Alg. 1, the
/// particle gradient of largest norm (total-order tie-break: independent of the scatter order).
template <int D, ShapeFunctionKind Kind>
void nodal_damage_gradient(StepState<D>& state) {
  PartitionState<D>& part = state.partition;
  const auto& P = state.problem.particles;
  auto add_damage = [&](std::int64_t p, const Stencil<D>& s) {
    if (P.damage[p] <= 0.0) return;
    for (int e = 0; e < s.count; ++e) {
      const std::size_t i = static_cast<std::size_t>(s.node[e]);
      part.node_damage_max[i] = std::max(part.node_damage_max[i], P.damage[p]);
    }
  };
  // Only damaged particles and those within reach of damage or a surface (a gradient) take part;
  // the others (most of a body's interior) need no stencil here.
  const auto takes_part = [&](std::int64_t p) {
    return P.damage[p] > 0.0 || part.particle_gradient[p].squaredNorm() > 0.0;
  };
  if (!state.plan.principal_rule) {
    scatter_particles_where<D, Kind>(state, takes_part, [&](std::int64_t p, const Stencil<D>& s) {
      add_damage(p, s);
      const Vec<D>& g = part.particle_gradient[p];
      if (g.squaredNorm() <= 0.0) return;
      for (int e = 0; e < s.count; ++e)
        fold_nodal_gradient<D>(g, part.node_gradient[static_cast<std::size_t>(s.node[e])]);
    });
    return;
  }
  scatter_particles_where<D, Kind>(state, takes_part, [&](std::int64_t p, const Stencil<D>& s) {
    add_damage(p, s);
    const Vec<D>& g = part.particle_gradient[p];
    if (g.squaredNorm() <= 0.0) return;
    for (int e = 0; e < s.count; ++e)
      if (s.weight[e] > 0.0)
        accumulate_gradient_tensor<D>(
            g, part.node_gradient_tensor[static_cast<std::size_t>(s.node[e])]);
  });
  const std::int64_t nodes = static_cast<std::int64_t>(part.node_gradient.size());
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < nodes; ++i)
    if (part.node_gradient_tensor[i].squaredNorm() > 0.0)
      part.node_gradient[i] = principal_gradient<D>(part.node_gradient_tensor[i]);
}

/// One byte per stencil entry: the field the particle uses at that node for the whole step. A node
/// without a nodal damage gradient keeps every particle in field 0, so it never has two fields.
template <int D, ShapeFunctionKind Kind>
void build_field_map(StepState<D>& state) {
  const auto& P = state.problem.particles;
  PartitionState<D>& part = state.partition;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  constexpr std::size_t stride = Stencil<D>::capacity;
  size_array(part.field_map, static_cast<std::size_t>(n) * stride);
  const bool by_bodies = state.plan.by_bodies;
#pragma omp parallel
  {
    Stencil<D> s;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      std::uint8_t* fields = part.field_map.data() + static_cast<std::size_t>(p) * stride;
      if (by_bodies) {
        // The field is the body: no stencil needed.
        std::fill(fields, fields + stride, static_cast<std::uint8_t>(P.body[p] == 0 ? 0 : 1));
        continue;
      }
      fill_stencil<D, Kind>(P, p, state.grid, s);
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        fields[e] = part.node_gradient[i].squaredNorm() > 0.0
                        ? static_cast<std::uint8_t>(field_of(state, p, i))
                        : 0;
      }
    }
  }
}

}  // namespace

template <int D>
void update_damage_field(StepState<D>& state) {
  const auto& P = state.problem.particles;
  PartitionState<D>& part = state.partition;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  size_array(part.particle_dhat, P.size());
  bool any = false;
#pragma omp parallel for reduction(|| : any) schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    part.particle_dhat[p] = std::max(static_cast<double>(P.surface[p]), P.damage[p]);
    any = any || part.particle_dhat[p] > 0.0;
  }
  part.this_step = any;
  if (!any) return;
  part.neighbours.update(P.x, state.kernel_radius, state.problem.contact.rebuild_fraction);
  damage_field_gradient<D>(part.neighbours, P.x, part.particle_dhat, state.kernel_radius,
                           part.particle_field, part.particle_gradient);
}

template <int D, ShapeFunctionKind Kind>
void partition_nodes(StepState<D>& state) {
  if (!state.plan.by_bodies) {
    nodal_damage_gradient<D, Kind>(state);
    band_sides<D, Kind>(state);
  }
  build_field_map<D, Kind>(state);
}

#define FRAGMPM_INSTANTIATE(D)                                                \
  template void update_damage_field<D>(StepState<D>&);                        \
  template void partition_nodes<D, ShapeFunctionKind::linear>(StepState<D>&); \
  template void partition_nodes<D, ShapeFunctionKind::ugimp>(StepState<D>&);  \
  template void partition_nodes<D, ShapeFunctionKind::cpdi>(StepState<D>&);   \
  template void partition_nodes<D, ShapeFunctionKind::bspline2>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
