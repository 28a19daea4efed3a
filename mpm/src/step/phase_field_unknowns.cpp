// Steps 1-2 of the phase-field stage: which fields reach each node, and their unknowns.
#include "step/particle_loops.hpp"
#include "step/phase_field_parts.hpp"

namespace fragmpm::mpm {

namespace {

/// Enters `field` in the slots of `node`; false when they are all taken by other fields.
template <int D>
inline bool register_field(PhaseFieldState<D>& pf, std::size_t node, std::int32_t field) {
  constexpr int K = PhaseFieldState<D>::slots;
  std::int32_t* fields = pf.node_body.data() + node * K;
  for (int k = 0; k < K; ++k) {
    if (fields[k] == field) return true;
    if (fields[k] < 0) {
      fields[k] = field;
      return true;
    }
  }
  return false;
}

}  // namespace

template <int D, ShapeFunctionKind Kind>
void number_phase_field_unknowns(StepState<D>& state) {
  PhaseFieldState<D>& pf = *state.phase_field;
  const auto& P = state.problem.particles;
  auto is_phase_field = [&](std::int64_t p) { return has_phase_field(state, p); };
  constexpr int K = PhaseFieldState<D>::slots;
  const std::size_t nodes = static_cast<std::size_t>(state.grid.node_count());

  // 1. The bodies that reach each node, in the scatter's fixed order (thread-count independent).
  //    Should more than `slots` bodies reach one node, this step's bodies share one field. Only
  //    the nodes are needed: with whole B-spline stencils, mostly their stores of weights and
  //    gradients, this pass took 3.6 % of the samples of `fragmpm bench --damage-laws-only` on two
  //    threads (the assembly 11.5 %), with the nodes alone 2.3 %.
  pf.shared_fields = false;
  auto field_of = [&](std::int64_t p) { return field_of_body(pf, P.body[p]); };
  for (int attempt = 0; attempt < 2; ++attempt) {
    reset_array(pf.node_body, nodes * K, std::int32_t{-1});
    int overflow = 0;
    scatter_particle_nodes_where<D, Kind>(
        state, is_phase_field,
        [&](std::int64_t p, const std::array<std::int64_t, Stencil<D>::capacity>& reached,
            int count) {
          const std::int32_t field = field_of(p);
          for (int e = 0; e < count; ++e)
            if (!register_field(pf, static_cast<std::size_t>(reached[e]), field)) {
#pragma omp atomic write
              overflow = 1;
            }
        });
    if (!overflow) break;
    pf.shared_fields = true;
  }

  // 2. Unknowns in node order (so the columns of every row come out sorted).
  size_array(pf.node_unknown, nodes * K);
  std::int64_t unknowns = 0;
  for (std::size_t slot = 0; slot < nodes * K; ++slot)
    pf.node_unknown[slot] = pf.node_body[slot] >= 0 ? static_cast<std::int32_t>(unknowns++) : -1;
  const std::size_t m = static_cast<std::size_t>(unknowns);
  size_array(pf.unknown_node, m);
  size_array(pf.unknown_body, m);
  for (std::size_t slot = 0; slot < nodes * K; ++slot)
    if (pf.node_unknown[slot] >= 0) {
      pf.unknown_node[static_cast<std::size_t>(pf.node_unknown[slot])] =
          static_cast<std::int64_t>(slot / K);
      pf.unknown_body[static_cast<std::size_t>(pf.node_unknown[slot])] = pf.node_body[slot];
    }
}

#define FRAGMPM_INSTANTIATE(D)                                                            \
  template void number_phase_field_unknowns<D, ShapeFunctionKind::linear>(StepState<D>&); \
  template void number_phase_field_unknowns<D, ShapeFunctionKind::ugimp>(StepState<D>&);  \
  template void number_phase_field_unknowns<D, ShapeFunctionKind::cpdi>(StepState<D>&);   \
  template void number_phase_field_unknowns<D, ShapeFunctionKind::bspline2>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
