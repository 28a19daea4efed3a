// The grid of one step: its active region, the sizes of its node arrays, the scatter strips, and
// the particle forces of traction loads.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "step/failure_text.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
std::optional<NumericalFailure> update_active_region(StepState<D>& state) {
  const auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  Vec<D> lower = Vec<D>::Constant(std::numeric_limits<double>::infinity());
  Vec<D> upper = -lower;
  std::int64_t outside = -1;
  double largest = 0.0;
  const Vec<D> domain_min = state.problem.grid.min, domain_max = state.problem.grid.max;
  const ShapeFunctionKind kind = state.problem.grid.shape_function;
#pragma omp parallel
  {
    Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
    double half_extent = 0.0;
    std::int64_t first_outside = -1;
#pragma omp for schedule(static) nowait
    for (std::int64_t p = 0; p < n; ++p) {
      Vec<D> a = P.x[p], b = P.x[p];
      stencil_bounds<D>(kind, P.x[p], P.domain[p], 0.5 * P.domain[p].diagonal().cwiseAbs(),
                        state.grid.cell_size, a, b);
      lo = lo.cwiseMin(a);
      hi = hi.cwiseMax(b);
      half_extent = std::max(half_extent, 0.5 * (b[0] - a[0]));
      if (first_outside < 0 && ((P.x[p] - domain_min).minCoeff() < 0.0 ||
                                (domain_max - P.x[p]).minCoeff() < 0.0 || !P.x[p].allFinite()))
        first_outside = p;
    }
#pragma omp critical(fragmpm_active_region)
    {
      lower = lower.cwiseMin(lo);
      upper = upper.cwiseMax(hi);
      largest = std::max(largest, half_extent);
      if (first_outside >= 0 && (outside < 0 || first_outside < outside)) outside = first_outside;
    }
  }
  if (outside >= 0) {
    NumericalFailure failure;
    failure.step = state.step;
    failure.time = state.time;
    failure.particle = outside;
    failure.what =
        "particle " + std::to_string(outside) + " (body " + std::to_string(P.body[outside]) +
        ") left the computational domain: x = " + format_vector<D>(P.x[outside]) + " m, domain " +
        format_vector<D>(domain_min) + " to " + format_vector<D>(domain_max) +
        " m, v = " + format_vector<D>(P.v[outside]) + " m/s";
    if (P.x[outside].allFinite())
      failure.what +=
          " ([grid] outside = \"remove\" takes particles that leave the domain out of the run "
          "instead of stopping it)";
    return failure;
  }
  GridIndex<D>& grid = state.grid;
  for (int k = 0; k < D; ++k) {
    const auto first = static_cast<std::int64_t>(
                           std::floor((lower[k] - grid.origin[k]) * grid.inverse_cell_size)) -
                       1;
    const auto last = static_cast<std::int64_t>(
                          std::floor((upper[k] - grid.origin[k]) * grid.inverse_cell_size)) +
                      2;
    grid.lower[k] = first;
    grid.extent[k] = last - first + 1;
  }
  state.order.largest_half_extent = largest * grid.inverse_cell_size;
  return std::nullopt;
}

template <int D>
void size_grid(StepState<D>& state) {
  const std::size_t nodes = static_cast<std::size_t>(state.grid.node_count());
  const int fields = state.fields();
  NodeFields<D>& N = state.nodes;
  for (int f = 0; f < fields; ++f) {
    reset_array(N.mass[f], nodes, 0.0);
    reset_array(N.momentum[f], nodes, Vec<D>::Zero().eval());
    reset_array(N.force[f], nodes, Vec<D>::Zero().eval());
    size_array(N.velocity_lumped[f], nodes);
    size_array(N.velocity[f], nodes);
    if (state.plan.wall_gap_test) reset_array(N.position[f], nodes, Vec<D>::Zero().eval());
  }
  if (state.plan.books_contact) reset_array(N.touched, nodes, std::uint8_t{0});
  if (!state.partition.this_step) return;
  PartitionState<D>& part = state.partition;
  ContactSums<D>& sums = state.contact;
  const StepPlan& plan = state.plan;
  reset_array(part.node_gradient, nodes, Vec<D>::Zero().eval());
  if (!plan.by_bodies && plan.principal_rule)
    reset_array(part.node_gradient_tensor, nodes, Mat<D>::Zero().eval());
  reset_array(sums.dhat_max, nodes, 0.0);
  if (!plan.by_bodies) {
    reset_array(part.node_damage_max, nodes, 0.0);
    for (int f = 0; f < 2; ++f) {
      reset_array(part.node_side_moment[f], nodes, Vec<D>::Zero().eval());
      reset_array(part.node_side_weight[f], nodes, 0.0);
    }
  }
  for (int f = 0; f < 2; ++f) {
    reset_array(sums.mass_gradient[f], nodes, Vec<D>::Zero().eval());
    reset_array(sums.dhat[f], nodes, 0.0);
    if (plan.gap_test) reset_array(sums.position[f], nodes, Vec<D>::Zero().eval());
    if (plan.needs_contact_area) reset_array(sums.volume_gradient[f], nodes, Vec<D>::Zero().eval());
  }
  // Per-node lists of the contact stage never outgrow the node count.
  if (sums.two_field_nodes.capacity() < nodes) {
    sums.two_field_nodes.reserve(nodes + nodes / 4);
    sums.friction_work.reserve(nodes + nodes / 4);
    sums.normal_impulse.reserve(nodes + nodes / 4);
    sums.area.reserve(nodes + nodes / 4);
  }
}

template <int D>
void bin_particles_into_strips(StepState<D>& state) {
  const auto& P = state.problem.particles;
  const GridIndex<D>& grid = state.grid;
  ScatterOrder& order = state.order;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  // A particle in cell c touches nodes c − ceil(e) … c + ceil(e) + 1 for half-extent e (cells).
  order.strip_width = 2 * static_cast<std::int64_t>(std::ceil(order.largest_half_extent)) + 2;
  const std::int64_t strips = (grid.extent[0] + order.strip_width - 1) / order.strip_width;
  reset_array(order.strip_start, static_cast<std::size_t>(strips + 1), std::int64_t{0});
  size_array(order.strip_of, static_cast<std::size_t>(n));
  size_array(order.strip_order, static_cast<std::size_t>(n));
  const std::int64_t width = order.strip_width;
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const std::int64_t cell = static_cast<std::int64_t>(std::floor((P.x[p][0] - grid.origin[0]) *
                                                                   grid.inverse_cell_size)) -
                              grid.lower[0];
    order.strip_of[p] = std::clamp<std::int64_t>(cell / width, 0, strips - 1);
  }
  for (std::int64_t p = 0; p < n; ++p) ++order.strip_start[order.strip_of[p] + 1];
  for (std::int64_t s = 0; s < strips; ++s) order.strip_start[s + 1] += order.strip_start[s];
  size_array(order.strip_cursor, static_cast<std::size_t>(strips));
  std::copy(order.strip_start.begin(), order.strip_start.end() - 1, order.strip_cursor.begin());
  for (std::int64_t p = 0; p < n; ++p)
    order.strip_order[order.strip_cursor[order.strip_of[p]]++] = p;
}

template <int D>
void update_load_forces(StepState<D>& state) {
  for (auto& f : state.load_force) f.setZero();
  for (const TractionLoad<D>& load : state.problem.loads) {
    const Vec<D> traction = load.traction(state.time);
    for (std::size_t k = 0; k < load.particles.size(); ++k)
      state.load_force[static_cast<std::size_t>(load.particles[k])] +=
          load.boundary_measure[k] * traction;
  }
}

#define FRAGMPM_INSTANTIATE(D)                                                     \
  template std::optional<NumericalFailure> update_active_region<D>(StepState<D>&); \
  template void size_grid<D>(StepState<D>&);                                       \
  template void bin_particles_into_strips<D>(StepState<D>&);                       \
  template void update_load_forces<D>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
