// Penalty walls ([XLS21] Remark 1, eq. (83), (86)-(87)): each particle whose domain reaches behind
// the plane gets the force κ_n A_p n, A_p the part of its domain behind the plane
// (fragmpm/mpm/penalty_contact.hpp), scattered to the grid with the particle's weights like a
// traction load. The forces are those of the particle state at the start of the step (explicit),
// so κ_n must stay below the stiffness the CFL step can carry. Estimate (not measured): a node of
// mass ρh² on a spring κ_n h alone is stable for ω Δt < 2, κ_n < 50 E / h at the default Courant
// number 0.4 (Δt = 0.28 h / c); with the material's own stiffness at the same node about half of
// that. κ_n = 10 E / h (the Hertz case, verify_hertz.cpp) keeps a margin. The wall reaction is −Σ_p
// κ_n A_p n, and the work of the forces on the particles is booked as wall work (g2p.cpp), so the
// energy stored in the penalty "spring" is in wall_work.
#include "fragmpm/mpm/penalty_contact.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
void apply_penalty_walls(StepState<D>& state) {
  const auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  size_array(state.penalty_force, P.size());
  std::fill(state.penalty_force.begin(), state.penalty_force.end(), Vec<D>::Zero());
  for (std::size_t w = 0; w < state.problem.walls.size(); ++w) {
    const WallSpec<D>& wall = state.problem.walls[w];
    if (wall.kind != WallKind::penalty) continue;
    const Vec<D> point = wall.point + wall.velocity.displacement(state.time);
    const Vec<D> normal = wall.normal;
    const double stiffness = wall.penalty_stiffness;
    auto& measure = state.penalty_measure;
    size_array(measure, P.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      measure[p] = penetration_measure<D>(P.x[p], P.domain[p], point, normal);
      if (measure[p] > 0.0) state.penalty_force[p] += stiffness * measure[p] * normal;
    }
    // Summed serially in particle order, so the reaction does not depend on the thread count.
    double measure_sum = 0.0;
    for (std::int64_t p = 0; p < n; ++p) measure_sum += measure[p];
    state.row.wall_force[w] = -stiffness * measure_sum * normal;  // force of the material on it
  }
}

template void apply_penalty_walls<2>(StepState<2>&);
template void apply_penalty_walls<3>(StepState<3>&);

}  // namespace fragmpm::mpm
