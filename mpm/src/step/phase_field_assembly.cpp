// Steps 3-4 of the phase-field stage: the nodal system of [KT19] eq. (56)-(57) by particle
// quadrature (phase_field_stage.cpp derives its entries), summed per node offset in the band and
// then compressed.
#include <cmath>

#include "step/particle_loops.hpp"
#include "step/phase_field_parts.hpp"

namespace fragmpm::mpm {

namespace {

/// Largest node offset between two entries of one particle's stencil, per direction.
template <int D, ShapeFunctionKind Kind>
int stencil_reach(const StepState<D>& state) {
  if constexpr (Kind == ShapeFunctionKind::linear) return 1;    // 2 nodes per direction
  if constexpr (Kind == ShapeFunctionKind::bspline2) return 2;  // 3 nodes
  // uGIMP and CPDI: a stencil spans the cells of its bounds, lower … upper + 1 (cells).
  const auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  double extent = 0.0;
  const ShapeFunctionKind kind = Kind;
#pragma omp parallel for reduction(max : extent) schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    Vec<D> lower, upper;
    stencil_bounds<D>(kind, P.x[p], P.domain[p], 0.5 * P.domain[p].diagonal().cwiseAbs(),
                      state.grid.cell_size, lower, upper);
    extent = std::max(extent, (upper - lower).maxCoeff() * state.grid.inverse_cell_size);
  }
  return static_cast<int>(std::ceil(extent)) + 1;
}

}  // namespace

template <int D, ShapeFunctionKind Kind>
void assemble_phase_field_system(StepState<D>& state) {
  PhaseFieldState<D>& pf = *state.phase_field;
  const auto& P = state.problem.particles;
  auto is_phase_field = [&](std::int64_t p) { return has_phase_field(state, p); };
  auto field_of = [&](std::int64_t p) { return field_of_body(pf, P.body[p]); };
  constexpr int K = PhaseFieldState<D>::slots;
  const GridIndex<D>& grid = state.grid;
  const std::size_t m = pf.unknown_node.size();
  const std::int64_t unknowns = static_cast<std::int64_t>(m);

  // 3. Particle quadrature of [KT19] eq. (57) and (52) into the band rows, and the volume-weighted
  //    projection of the particles' d as the initial guess.
  pf.reach = stencil_reach<D, Kind>(state);
  pf.band_width = 1;
  for (int k = 0; k < D; ++k) pf.band_width *= 2 * pf.reach + 1;
  const int width = pf.band_width, reach = pf.reach;
  const std::int64_t centre = band_index<D>(IVec<D>::Zero(), reach);
  // The band (m × 25 doubles with the B-spline in 2D, 5 MB at 10⁵ particles) is cleared by all
  // threads: cleared by one, it was 0.6 % of the cubic bench rows' samples on two threads.
  size_array(pf.band, m * static_cast<std::size_t>(width));
  {
    const std::int64_t band_size = static_cast<std::int64_t>(pf.band.size());
    double* band = pf.band.data();
#pragma omp parallel for schedule(static)
    for (std::int64_t k = 0; k < band_size; ++k) band[k] = 0.0;
  }
  reset_array(pf.guess_weight, m, 0.0);
  if (pf.rhs.size() != unknowns) {
    pf.rhs.resize(unknowns);
    pf.guess.resize(unknowns);
    pf.solution.resize(unknowns);
  }
  pf.rhs.setZero();
  pf.guess.setZero();
  std::vector<char>& stiff = pf.solver.preconditioner().stiff;
  reset_array(stiff, m, char{0});
  scatter_particles_where<D, Kind>(state, is_phase_field, [&](std::int64_t p, const Stencil<D>& s) {
    const std::size_t material = static_cast<std::size_t>(P.material[p]);
    const double volume = P.volume0[p];
    const double drive = pf.drive_factor[material] * P.damage_history[p];  // (1 − k_f) H
    const double source = volume * pf.local_coefficient[material];         // V G_c / (4 l₀)
    const double local = source + volume * drive;
    const double diffusion = volume * pf.gradient_coefficient[material];
    const Mat<D> to_reference = P.F[p].transpose();  // ∇_X S̄ = Fᵀ ∇_x S̄
    // The entries that reach an unknown, packed: their rows, weights, reference gradients and
    // positions in the band, band_index(node_f − node_e) = place_f − place_e + centre (the band
    // index is linear in the offset). One division per entry finds a node's coordinates.
    std::array<std::int32_t, Stencil<D>::capacity> row;
    std::array<std::int64_t, Stencil<D>::capacity> place;
    std::array<double, Stencil<D>::capacity> weight;
    std::array<Vec<D>, Stencil<D>::capacity> gradient;
    std::array<int, Stencil<D>::capacity> entry_of;
    int used = 0;
    for (int e = 0; e < s.count; ++e) {
      if (empty_entry(s, e)) continue;
      const std::size_t i = static_cast<std::size_t>(s.node[e]);
      row[used] = pf.node_unknown[i * K + static_cast<std::size_t>(slot_of(pf, i, field_of(p)))];
      if (row[used] < 0) continue;
      std::int64_t rest = s.node[e], stride = 1;
      place[used] = 0;
      for (int k = 0; k < D; ++k) {
        const std::int64_t coordinate = k + 1 < D ? rest % grid.extent[k] : rest;
        rest = k + 1 < D ? rest / grid.extent[k] : 0;
        place[used] += coordinate * stride;
        stride *= 2 * reach + 1;
      }
      weight[used] = s.weight[e];
      gradient[used] = to_reference * s.gradient[e];
      entry_of[used] = e;
      ++used;
    }
    const bool cracked = drive > stiff_history_ratio * pf.local_coefficient[material];
    for (int a = 0; a < used; ++a) {
      const std::size_t r = static_cast<std::size_t>(row[a]);
      if (cracked) stiff[r] = 1;
      pf.rhs[row[a]] += source * weight[a];
      pf.guess[row[a]] += volume * weight[a] * (1.0 - P.damage[p]);
      pf.guess_weight[r] += volume * weight[a];
    }
    // K_ab is symmetric: each pair is computed once and added to both rows.
    if (!has_fourth_order<D, Kind>(pf, material)) {
      for (int a = 0; a < used; ++a) {
        double* band_a = pf.band.data() + static_cast<std::size_t>(row[a]) * width + centre;
        const double local_a = local * weight[a];
        const Vec<D> diffusion_a = diffusion * gradient[a];
        band_a[0] += local_a * weight[a] + diffusion_a.dot(gradient[a]);
        for (int b = a + 1; b < used; ++b) {
          const double entry = local_a * weight[b] + diffusion_a.dot(gradient[b]);
          const std::int64_t offset = place[b] - place[a];
          band_a[offset] += entry;
          pf.band[static_cast<std::size_t>(row[b]) * width + centre - offset] += entry;
        }
      }
      return;
    }
    // The fourth-order term ([KT19] eq. (57), scaled by G_c/(4 l₀)): V G_c l₀³ χ_aᵀ Γ_g χ_b with χ
    // the reference-configuration second derivatives (Fᵀ H F, F taken uniform over the stencil).
    // With v_a = (S̄_a, ∇S̄_a, χ_a) the whole entry is v_aᵀ W v_b, W = diag(local, diffusion I,
    // V Γ_g) symmetric (Γ_g = Tᵀ γ T, phase_field.cpp): each pair is one 6-term product of
    // y_a = W v_a with v_b, computed once and added to both rows.
    std::array<Eigen::Vector3d, Stencil<D>::capacity> chi{};
    if constexpr (D == 2) bspline2_reference_curvatures(P.x[p], P.F[p], grid, chi);
    constexpr int terms = 1 + D + 3;
    std::array<Eigen::Matrix<double, terms, 1>, Stencil<D>::capacity> v, y;
    const Eigen::Matrix3d curvature_weight = volume * pf.fourth_order[material];
    for (int a = 0; a < used; ++a) {
      const Eigen::Vector3d& chi_a = chi[entry_of[a]];
      v[a] << weight[a], gradient[a], chi_a;
      y[a] << local * weight[a], diffusion * gradient[a], curvature_weight * chi_a;
    }
    for (int a = 0; a < used; ++a) {
      double* band_a = pf.band.data() + static_cast<std::size_t>(row[a]) * width + centre;
      band_a[0] += y[a].dot(v[a]);
      for (int b = a + 1; b < used; ++b) {
        const double entry = y[a].dot(v[b]);
        const std::int64_t offset = place[b] - place[a];
        band_a[offset] += entry;
        pf.band[static_cast<std::size_t>(row[b]) * width + centre - offset] += entry;
      }
    }
  });

  // 4. Compressed rows: the non-zero offsets of each band row, the column being the same body's
  //    unknown at the offset node. A row without weight (a node only zero-gradient entries
  //    touch) keeps c = 1 (d = 0) through a unit diagonal.
  size_array(pf.outer, m + 1);
  pf.outer[0] = 0;
#pragma omp parallel for schedule(static)
  for (std::int64_t rr = 0; rr < unknowns; ++rr) {
    const double* band = pf.band.data() + static_cast<std::size_t>(rr) * width;
    int count = 0;
    for (int b = 0; b < width; ++b) count += band[b] != 0.0;
    pf.outer[static_cast<std::size_t>(rr) + 1] = std::max(count, 1);
  }
  for (std::size_t r = 0; r < m; ++r) pf.outer[r + 1] += pf.outer[r];
  const std::size_t nonzeros = static_cast<std::size_t>(pf.outer[m]);
  size_array(pf.inner, nonzeros);
  size_array(pf.values, nonzeros);
#pragma omp parallel for schedule(static)
  for (std::int64_t rr = 0; rr < unknowns; ++rr) {
    const std::size_t r = static_cast<std::size_t>(rr);
    const double* band = pf.band.data() + r * static_cast<std::size_t>(width);
    std::size_t at = static_cast<std::size_t>(pf.outer[r]);
    if (pf.outer[r + 1] - pf.outer[r] == 1 && band[centre] == 0.0) {
      pf.inner[at] = static_cast<int>(r);
      pf.values[at] = 1.0;
      pf.rhs[rr] = 1.0;
      continue;
    }
    const IVec<D> here = grid.global(pf.unknown_node[r]);
    const std::int32_t body = pf.unknown_body[r];
    for (int b = 0; b < width; ++b) {
      if (band[b] == 0.0) continue;
      IVec<D> there = here;
      for (int k = 0, rest = b; k < D; ++k, rest /= 2 * reach + 1)
        there[k] += rest % (2 * reach + 1) - reach;
      const std::size_t j = static_cast<std::size_t>(grid.linear(there));
      pf.inner[at] = pf.node_unknown[j * K + static_cast<std::size_t>(slot_of(pf, j, body))];
      pf.values[at] = band[b];
      ++at;
    }
  }
}

#define FRAGMPM_INSTANTIATE(D)                                                            \
  template void assemble_phase_field_system<D, ShapeFunctionKind::linear>(StepState<D>&); \
  template void assemble_phase_field_system<D, ShapeFunctionKind::ugimp>(StepState<D>&);  \
  template void assemble_phase_field_system<D, ShapeFunctionKind::cpdi>(StepState<D>&);   \
  template void assemble_phase_field_system<D, ShapeFunctionKind::bspline2>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
