#pragma once
// The two ways the stages visit particles with their stencils: scatter loops (strip by strip in two
// parity passes, race-free and summing in a thread-independent order, see ScatterOrder) and
// gather loops (any order; each particle writes only itself).
#include <array>
#include <cstdint>

#include "step/step_state.hpp"

namespace fragmpm::mpm {

/// Offsets: also fill the node offsets x_i − x_p (the APIC transfer).
template <int D, ShapeFunctionKind Kind, bool Offsets = false>
inline void fill_stencil(const Particles<D>& P, std::int64_t p, const GridIndex<D>& grid,
                         Stencil<D>& s) {
  if constexpr (Kind == ShapeFunctionKind::linear)
    linear_stencil<D, Offsets>(P.x[p], grid, s);
  else if constexpr (Kind == ShapeFunctionKind::ugimp)
    ugimp_stencil<D, Offsets>(P.x[p], 0.5 * P.domain[p].diagonal().cwiseAbs(), grid, s);
  else if constexpr (Kind == ShapeFunctionKind::bspline2)
    bspline2_stencil<D, Offsets>(P.x[p], grid, s);
  else
    cpdi_stencil<D, Offsets>(P.x[p], P.domain[p], grid, s);
}

/// A stencil entry that contributes nothing (zero weight and gradient, e.g. the B-spline's end
/// knot): the phase field skips it, so it never creates an unknown with an empty row.
template <int D>
inline bool empty_entry(const Stencil<D>& s, int e) {
  return s.weight[e] == 0.0 && s.gradient[e].squaredNorm() == 0.0;
}

/// Runs visit(p, scratch) over the particles p with keep(p), strip by strip in two parity passes,
/// so that visits scattering into p's stencil nodes never race; `scratch` is one Scratch per
/// thread, for the stencil the visit fills.
template <int D, class Scratch, class Keep, class Visit>
void for_each_in_scatter_order(const StepState<D>& state, Keep&& keep, Visit&& visit) {
  const ScatterOrder& order = state.order;
  const std::int64_t strips = static_cast<std::int64_t>(order.strip_start.size()) - 1;
#pragma omp parallel
  {
    Scratch scratch;
    for (std::int64_t parity = 0; parity < 2; ++parity) {
      // The implicit barrier at the end of the loop separates the two parities.
#pragma omp for schedule(dynamic, 1)
      for (std::int64_t strip = parity; strip < strips; strip += 2) {
        for (std::int64_t k = order.strip_start[strip]; k < order.strip_start[strip + 1]; ++k) {
          const std::int64_t p = order.strip_order[k];
          if (keep(p)) visit(p, scratch);
        }
      }
    }
  }
}

/// Runs body(p, stencil) over the particles p with keep(p) in the scatter order above. No stencil
/// is built for the others.
template <int D, ShapeFunctionKind Kind, bool Offsets = false, class Keep, class Body>
void scatter_particles_where(const StepState<D>& state, Keep&& keep, Body&& body) {
  for_each_in_scatter_order<D, Stencil<D>>(state, keep, [&](std::int64_t p, Stencil<D>& s) {
    fill_stencil<D, Kind, Offsets>(state.problem.particles, p, state.grid, s);
    body(p, s);
  });
}

/// Runs body(p, nodes, count) over the particles p with keep(p) in the same order, with the nodes
/// of p's stencil that carry a weight or a gradient.
template <int D, ShapeFunctionKind Kind, class Keep, class Body>
void scatter_particle_nodes_where(const StepState<D>& state, Keep&& keep, Body&& body) {
  using Nodes = std::array<std::int64_t, Stencil<D>::capacity>;
  if constexpr (Kind == ShapeFunctionKind::bspline2) {
    for_each_in_scatter_order<D, Nodes>(state, keep, [&](std::int64_t p, Nodes& nodes) {
      body(p, nodes, bspline2_stencil_nodes<D>(state.problem.particles.x[p], state.grid, nodes));
    });
  } else {
    scatter_particles_where<D, Kind>(state, keep, [&](std::int64_t p, const Stencil<D>& s) {
      Nodes nodes;
      int count = 0;
      for (int e = 0; e < s.count; ++e)
        if (!empty_entry(s, e)) nodes[count++] = s.node[e];
      body(p, nodes, count);
    });
  }
}

template <int D, ShapeFunctionKind Kind, bool Offsets = false, class Body>
void scatter_particles(const StepState<D>& state, Body&& body) {
  scatter_particles_where<D, Kind, Offsets>(
      state, [](std::int64_t) { return true; }, body);
}

/// Field of entry e of particle p's stencil this step (0 unless the step is partitioned).
template <int D, bool Partitioned>
inline int field_at(const StepState<D>& state, std::int64_t p, int e) {
  if constexpr (Partitioned)
    return state.partition.field_map[static_cast<std::size_t>(p) * Stencil<D>::capacity +
                                     static_cast<std::size_t>(e)];
  else
    return 0;
}

}  // namespace fragmpm::mpm
