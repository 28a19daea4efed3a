// Nonlocal Rankine damage: the law of [XLS21] eq. (19)-(21) driven by a kernel average of the
// trial largest principal stress instead of the particle's own value ([PCB87]; docs/design.md,
// "Nonlocal Rankine").
//
// Why: with the local law the strain localises in whatever band the discretisation allows, one
// particle row where the row's particles can move apart and a cell where they share a node's
// velocity, so the band width (and with it the dissipation G_f / l_ch × width) depends on how the
// crack meets the grid. Averaging the driving stress over a disk of fixed radius r (here the cell
// diagonal, the damage field's radius [HH17] §2.2) damages every particle within about r of the
// peak together: the band is as wide as the averaging, whatever the loading, and l_ch is
// calibrated once against it (problem.hpp, rankine_nonlocal_band_cells).
//
//   σ̄₁(x_p) = Σ_q ω(r̄_pq) V_q σ₁_q / Σ_q ω(r̄_pq) V_q,   r̄_pq = |x_p − x_q| / r,
//
// with the kernel ω of [HH17] eq. (18), over p itself and its listed neighbours of the same body
// and material. The trial (undamaged) stress is averaged, as [PCB87] averages the undamaged
// quantity: a softening particle keeps driving its neighbours until the band is formed. Failed
// particles (d = 1) give nothing: their trial stress measures only how far the crack has opened,
// and would otherwise push the band ever wider.
#include <omp.h>

#include <cmath>
#include <limits>

#include "fragmpm/mpm/damage_field.hpp"
#include "step/constitutive_update.hpp"
#include "step/failed_domain.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D, bool Thermal>
ConstitutiveSums nonlocal_constitutive_update(StepState<D>& state, double dt, bool limit_domains) {
  auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  const double radius = state.kernel_radius;
  NeighbourLists<D>& lists = state.partition.neighbours;
  lists.update(P.x, radius, state.problem.contact.rebuild_fraction);
  size_array(state.nonlocal_equivalent, P.size());
  const auto& local = state.local_equivalent;
  const auto& is_nonlocal = state.material_nonlocal;

  // The averages read the damage of this step's start: all of them first, then the updates.
#pragma omp parallel for schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const std::size_t i = static_cast<std::size_t>(p);
    double& average = state.nonlocal_equivalent[i];
    average = std::numeric_limits<double>::quiet_NaN();
    if (!is_nonlocal[static_cast<std::size_t>(P.material[p])] || P.damage[p] >= 1.0) continue;
    double weighted = P.volume0[p] * local[i], weight = P.volume0[p];
    for (const std::uint32_t q : lists.neighbours(i)) {
      if (P.body[q] != P.body[p] || P.material[q] != P.material[p] || P.damage[q] >= 1.0) continue;
      const double w = damage_kernel((P.x[q] - P.x[p]).norm() / radius) * P.volume0[q];
      weighted += w * local[q];
      weight += w;
    }
    average = weighted / weight;
  }

  const double cell_size = state.grid.cell_size;
  double stored = 0.0, dissipated = 0.0, flowed = 0.0;
#pragma omp parallel for schedule(static) reduction(+ : stored, dissipated, flowed)
  for (std::int64_t p = 0; p < n; ++p) {
    if (!is_nonlocal[static_cast<std::size_t>(P.material[p])]) continue;
    // A failed particle (NaN average) runs the local update, which leaves d = 1.
    const ConstitutiveResult energy = update_constitutive<D, Thermal, true>(
        state, p, dt, state.nonlocal_equivalent[static_cast<std::size_t>(p)]);
    stored += P.volume0[p] * energy.stored;
    dissipated += P.volume0[p] * energy.dissipated;
    flowed += P.volume0[p] * energy.flowed;
    if (limit_domains && P.damage[p] >= 1.0)
      settle_failed_domain<D>(P.domain[p], P.volume0[p] * P.F[p].determinant(),
                              state.material_failed_fluid[static_cast<std::size_t>(P.material[p])],
                              cell_size);
  }
  return {stored, dissipated, flowed};
}

#define FRAGMPM_INSTANTIATE(D)                                                                   \
  template ConstitutiveSums nonlocal_constitutive_update<D, false>(StepState<D>&, double, bool); \
  template ConstitutiveSums nonlocal_constitutive_update<D, true>(StepState<D>&, double, bool);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
