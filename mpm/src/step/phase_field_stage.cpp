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
// G_c per reference crack area instead of growing with the stretch of its particles.
#include <algorithm>
#include <cmath>
#include <limits>

#include "step/particle_loops.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

namespace {

/// The slot of node i that holds `field` (a body, or 0 when the bodies share one field).
template <int D>
inline int slot_of(const PhaseFieldState<D>& pf, std::size_t node, std::int32_t field) {
  constexpr int K = PhaseFieldState<D>::slots;
  const std::int32_t* fields = pf.node_body.data() + node * K;
  for (int s = 0; s < K - 1; ++s)
    if (fields[s] == field) return s;
  return K - 1;
}

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

/// Index of node offset o ∈ [−reach, reach]^D in a row of the band.
template <int D>
inline int band_index(const IVec<D>& offset, int reach) {
  int index = 0, stride = 1;
  for (int k = 0; k < D; ++k) {
    index += static_cast<int>(offset[k] + reach) * stride;
    stride *= 2 * reach + 1;
  }
  return index;
}

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

/// The fourth-order anisotropic term is on for this material (only compiled where it can be: the
/// B-spline in 2D).
template <int D, ShapeFunctionKind Kind>
inline bool has_fourth_order(const PhaseFieldState<D>& pf, std::size_t material) {
  if constexpr (D == 2 && Kind == ShapeFunctionKind::bspline2)
    return pf.anisotropic[material] != 0;
  else
    return (void)pf, (void)material, false;
}

}  // namespace

template <int D, ShapeFunctionKind Kind>
void solve_phase_field(StepState<D>& state) {
  PhaseFieldState<D>& pf = *state.phase_field;
  auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  const auto& kind_of = state.material_damages;
  auto is_phase_field = [&](std::int64_t p) {
    return kind_of[static_cast<std::size_t>(P.material[p])] == material_phase_field;
  };

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

  constexpr int K = PhaseFieldState<D>::slots;
  const GridIndex<D>& grid = state.grid;
  const std::size_t nodes = static_cast<std::size_t>(grid.node_count());

  // 1. The bodies that reach each node, in the scatter's fixed order (thread-count independent).
  //    Should more than `slots` bodies reach one node, this step's bodies share one field. Only
  //    the nodes are needed: with whole B-spline stencils, mostly their stores of weights and
  //    gradients, this pass took 3.6 % of the samples of `fragmpm bench --damage-laws-only` on two
  //    threads (the assembly 11.5 %), with the nodes alone 2.3 %.
  bool shared = false;
  auto field_of = [&](std::int64_t p) { return shared ? std::int32_t{0} : P.body[p]; };
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
    shared = true;
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

  // 5. Conjugate gradients ([KT19] §4.3: tol_c = 10⁻⁶); K is symmetric positive semi-definite
  //    (a weighted mass matrix plus a Laplacian by particle quadrature, phase_field_state.hpp),
  //    with f clear of its null space (f is a sum of the particles' rows). They start from the last
  //    step's nodal c where the same node and field had an unknown (the particles moved a fraction
  //    of a cell since, so it is the nearer guess: on the rings' system it halves the Jacobi
  //    iterations), extrapolated linearly, 2 c − c_previous, where the solve before that had the
  //    unknown too, and elsewhere from the particles' projected c = 1 − d. The field changes
  //    smoothly from step to step (the history H grows by the strain of one step), so the
  //    extrapolation leaves a residual of second order in Δt where the last solution leaves one of
  //    first order: on the cubic plate at h = 0.25 mm it cut the iterations of the first 200 solves
  //    from 92.7 to 55.6 a solve, with the same energies to six digits. The tolerance, not the
  //    start, sets the solution.
  for (std::size_t r = 0; r < m; ++r)
    pf.guess[static_cast<Eigen::Index>(r)] =
        pf.guess_weight[r] > 0.0 ? pf.guess[static_cast<Eigen::Index>(r)] / pf.guess_weight[r]
                                 : 1.0;
  pf.carried.assign(m, std::numeric_limits<double>::quiet_NaN());
  const bool extrapolate = pf.last.previous.size() == pf.last.solution.size();
  for (std::size_t k = 0; k < pf.last.solution.size(); ++k) {
    const IVec<D>& node = pf.last.node[k];
    if (((node - grid.lower).array() < 0).any() ||
        ((node - grid.lower).array() >= grid.extent.array()).any())
      continue;
    const std::size_t i = static_cast<std::size_t>(grid.linear(node));
    for (int slot = 0; slot < K; ++slot)
      if (pf.node_body[i * K + static_cast<std::size_t>(slot)] == pf.last.field[k]) {
        const Eigen::Index r = pf.node_unknown[i * K + static_cast<std::size_t>(slot)];
        const double last = pf.last.solution[k];
        pf.carried[static_cast<std::size_t>(r)] = last;
        const double previous = extrapolate ? pf.last.previous[k] : last;
        pf.guess[r] = std::isfinite(previous) ? 2.0 * last - previous : last;
        break;
      }
  }
  const Eigen::Map<const typename PhaseFieldState<D>::Matrix> matrix(
      unknowns, unknowns, static_cast<Eigen::Index>(nonzeros), pf.outer.data(), pf.inner.data(),
      pf.values.data());
  // Which solve: conjugate gradients with the crack block (phase_field_state.hpp). Should they
  // reach `phase_field_iteration_limit` iterations unconverged, the symbolic analysis of K (which
  // a factorisation needs anyway, and which depends on the pattern alone) says what one
  // factorisation would cost in iterations, and they go on from where they stopped while the
  // iterations so far cost less (factorisation_cost_in_iterations); only then is the step solved
  // directly, so every step's c meets the tolerance. A stall right after a direct step makes the
  // next steps direct as well, in runs that double (phase_field_warm_start.hpp). The weighing
  // matters on large systems with the fourth-order term: on the orthotropic plate's at
  // h = 0.125 mm the Jacobi conjugate gradients converge in 402 and 798 iterations at steps 3
  // and 40 (425 and 839 when stopped at 300 and resumed), the factorisation costs 1 107.
  bool analysed_now = false;  // this step's pattern was analysed in this step
  const auto analyse = [&](const Eigen::Map<const typename PhaseFieldState<D>::ColumnMatrix>& k) {
    // The AMD ordering and the symbolic analysis depend on the pattern alone; a step whose
    // unknowns and couplings are the last step's skips them (in a profile of the sphere-beam at
    // h = 0.125 mm with the crack open they were about 5 % of the samples, the numeric
    // factorisation 56 %).
    if (pf.analysed_outer != pf.outer || pf.analysed_inner != pf.inner) {
      pf.direct_solver.analyzePattern(k);
      pf.analysed_outer = pf.outer;
      pf.analysed_inner = pf.inner;
      analysed_now = true;
    }
    pf.pattern_reused = !analysed_now;
  };
  const auto solve_directly = [&]() -> bool {
    // The direct solve, of K + ε diag(K) with ε = phase_field_pivot_shift: K is only semi-definite
    // (phase_field_state.hpp), and unshifted its LDLᵀ pivots of the directions no particle sees
    // fall to rounding noise of either sign, which now and then leaves a residual far above the
    // tolerance. The shift lifts them to 10⁻¹² of their diagonal, a thousand times the rounding,
    // and moves nothing a particle sees by more than the tolerance: on the rings' systems at 300
    // and 450 µs the residual against K stays at 4 × 10⁻¹¹ and 2 × 10⁻¹⁰, and the particles' c
    // differ from the unshifted solve's by 5 × 10⁻¹⁰ and 1.4 × 10⁻⁸ (from the exact solution,
    // Jacobi's 10⁻⁶ leaves 10⁻⁷ and 10⁻⁵). Should the residual still miss the tolerance,
    // conjugate gradients solve the step.
    size_array(pf.shifted_values, nonzeros);
#pragma omp parallel for schedule(static)
    for (std::int64_t rr = 0; rr < unknowns; ++rr)
      for (int at = pf.outer[static_cast<std::size_t>(rr)];
           at < pf.outer[static_cast<std::size_t>(rr) + 1]; ++at)
        pf.shifted_values[static_cast<std::size_t>(at)] =
            pf.values[static_cast<std::size_t>(at)] *
            (pf.inner[static_cast<std::size_t>(at)] == rr ? 1.0 + phase_field_pivot_shift : 1.0);
    const Eigen::Map<const typename PhaseFieldState<D>::ColumnMatrix> shifted(
        unknowns, unknowns, static_cast<Eigen::Index>(nonzeros), pf.outer.data(), pf.inner.data(),
        pf.shifted_values.data());
    analyse(shifted);
    pf.direct_solver.factorize(shifted);
    if (pf.direct_solver.info() == Eigen::Success) {
      pf.solution = pf.direct_solver.solve(pf.rhs);
      if (pf.solution.allFinite()) {
        pf.residual = (matrix * pf.solution - pf.rhs).norm() / pf.rhs.norm();
        return pf.residual <= phase_field_tolerance;
      }
    }
    return false;
  };
  // The preconditioner (the crack block, or multigrid once the crack-block solves needed more
  // than multigrid_switch_iterations on average) is built once a step, when first needed.
  PhaseFieldWarmStart<D>& next = pf.last;
  pf.multigrid = pf.preconditioner == PhaseFieldPreconditioner::multigrid ||
                 (pf.preconditioner == PhaseFieldPreconditioner::automatic && next.multigrid != 0);
  bool preconditioned = false;
  const auto run = [&](auto& solver, int limit) {
    solver.setTolerance(phase_field_tolerance);
    solver.setMaxIterations(limit);
    if (!preconditioned) solver.compute(matrix);
    preconditioned = true;
    pf.solution = solver.solveWithGuess(pf.rhs, pf.guess);
    pf.iterations += static_cast<int>(solver.iterations());
    pf.residual = solver.error();
    return solver.info() == Eigen::Success;
  };
  // Multigrid levels are kept from an earlier step's system while the unknowns are the same and
  // the solves stay as quick as the first with them (keep_multigrid_levels): the finest level
  // smooths with this step's K and diagonal, so the V-cycle stays a symmetric operator, and only
  // its coarse correction is the older system's. Should a solve with kept levels not converge
  // within three times the V-cycles of the first (the older coarse system no longer fits), the
  // levels are built from this step's system and the solve starts again from the same guess. The
  // warm start keeps the system the levels came from, so that a restarted run builds the same.
  bool multigrid_used = false, levels_built_now = false;
  int cycles_since_build = 0;
  const auto build_levels_from = [&](AggregationMultigrid& multigrid, int rows, const int* outer,
                                     const int* inner, const double* values) {
    multigrid.reuse_levels = false;
    multigrid.compute(Eigen::Map<const typename PhaseFieldState<D>::Matrix>(rows, rows, outer[rows],
                                                                            outer, inner, values));
  };
  const auto iterate = [&](int limit) {
    if (!pf.multigrid) return run(pf.solver, limit);
    AggregationMultigrid& multigrid = pf.multigrid_solver.preconditioner();
    if (!preconditioned) {
      multigrid_used = true;
      size_array(multigrid.coordinates, m);
      size_array(multigrid.fields, m);
      bool same_unknowns = next.node.size() == m;
      for (std::size_t r = 0; r < m; ++r) {
        const IVec<D> node = grid.global(pf.unknown_node[r]);
        std::array<std::int64_t, 3> coordinates{0, 0, 0};
        for (int k = 0; k < D; ++k) coordinates[static_cast<std::size_t>(k)] = node[k];
        multigrid.coordinates[r] = coordinates;
        multigrid.fields[r] = pf.unknown_body[r];
        same_unknowns =
            same_unknowns && next.node[r] == node && next.field[r] == pf.unknown_body[r];
      }
      pf.levels_kept = keep_multigrid_levels(next, same_unknowns);
      if (pf.levels_kept && !pf.levels_held)  // a restart: the same levels from the same system
        build_levels_from(multigrid, static_cast<int>(m), next.levels_outer.data(),
                          next.levels_inner.data(), next.levels_values.data());
      multigrid.reuse_levels = pf.levels_kept;
      levels_built_now = !pf.levels_kept;
      if (pf.levels_kept) {
        const int trial = std::min(limit, std::max(30, 3 * static_cast<int>(next.levels_cycles)));
        const int before = pf.iterations;
        if (run(pf.multigrid_solver, trial)) return true;
        limit -= pf.iterations - before;
        multigrid.reuse_levels = false;
        preconditioned = false;
        pf.levels_kept = false;
        levels_built_now = true;
      }
    }
    const int before = pf.iterations;
    const bool converged = run(pf.multigrid_solver, limit);
    cycles_since_build += pf.iterations - before;
    return converged;
  };
  const auto preconditioner_multiply_adds = [&] {
    return pf.multigrid ? pf.multigrid_solver.preconditioner().multiply_adds()
                        : 2.0 * pf.solver.preconditioner().factor_nonzeros();
  };
  pf.iterations = 0;
  pf.levels_kept = false;
  pf.stopped_at_limit = false;
  pf.went_past_limit = false;
  if (next.direct_solves_left > 0) {
    --next.direct_solves_left;
    pf.direct = solve_directly();
    if (!pf.direct) iterate(2 * static_cast<int>(unknowns));
  } else if (iterate(pf.iteration_limit)) {
    pf.direct = false;
    next.direct_run = 0;
  } else {
    // The pattern's analysis (kept for the factorisation, which uses the same pattern) and this
    // step's crack block: both functions of this step's system, so a restarted run weighs alike.
    analyse(Eigen::Map<const typename PhaseFieldState<D>::ColumnMatrix>(
        unknowns, unknowns, static_cast<Eigen::Index>(nonzeros), pf.outer.data(), pf.inner.data(),
        pf.values.data()));
    pf.factorisation_iterations = factorisation_cost_in_iterations(
        pf.direct_solver.squared_column_counts(), static_cast<double>(nonzeros),
        static_cast<double>(unknowns), preconditioner_multiply_adds());
    const int budget = static_cast<int>(
        std::min(pf.factorisation_iterations, 2.0 * static_cast<double>(unknowns)));
    if (pf.weigh_factorisation && budget > pf.iterations) {
      pf.guess = pf.solution;
      pf.went_past_limit = iterate(budget - pf.iterations);
    }
    if (pf.went_past_limit) {
      pf.direct = false;
      next.direct_run = 0;
    } else {
      pf.stopped_at_limit = true;
      begin_direct_run(next);
      pf.direct = solve_directly();
      // Should the factorisation miss the tolerance too, the iteration goes on from the latest c.
      if (!pf.direct) {
        pf.guess = pf.solution;
        iterate(2 * static_cast<int>(unknowns));
      }
    }
  }
  // Crack-block solves that need this many iterations on average say the system has outgrown the
  // block: the fourth-order term's h⁻⁴ or open cracks across a large grid
  // (aggregation_multigrid.hpp). The history only grows, so the run keeps multigrid from here on;
  // the warm start carries the average and the choice through checkpoints.
  if (pf.preconditioner == PhaseFieldPreconditioner::automatic && !pf.multigrid &&
      (pf.iterations > 0 || !pf.direct) &&
      average_iterations_call_for_multigrid(next.average_iterations, pf.iterations))
    next.multigrid = 1;
  if (multigrid_used && !pf.direct) {
    if (levels_built_now) {
      next.levels_outer = pf.outer;
      next.levels_inner = pf.inner;
      next.levels_values = pf.values;
      next.levels_age = 1;
      next.levels_cycles = cycles_since_build;
    } else {
      ++next.levels_age;
    }
    next.last_cycles = pf.iterations;
    pf.levels_held = true;
  } else {
    next.levels_outer.clear();
    next.levels_inner.clear();
    next.levels_values.clear();
    next.levels_age = next.levels_cycles = next.last_cycles = 0;
    pf.levels_held = false;
    pf.levels_kept = false;
  }
  pf.last.node.resize(m);
  pf.last.field.resize(m);
  pf.last.solution.resize(m);
  pf.last.previous.resize(m);
  for (std::size_t r = 0; r < m; ++r) {
    pf.last.node[r] = grid.global(pf.unknown_node[r]);
    pf.last.field[r] = pf.unknown_body[r];
    pf.last.solution[r] = pf.solution[static_cast<Eigen::Index>(r)];
    pf.last.previous[r] = pf.direct ? std::numeric_limits<double>::quiet_NaN() : pf.carried[r];
  }
  // A direct solve is not extrapolated from. In the directions of K that no particle sees the
  // conjugate gradients keep whatever their guess holds, while the factorisation of the shifted
  // system gives them values of its own (rounding over the shift, unrelated to the last guess).
  // The change from the last solution then holds that jump, which is no trend of the field, and
  // 2 c − c_previous would repeat it at every later step (θ = 1 in c + θ (c − c_previous) keeps
  // every such change for good). The next solve therefore starts from the direct solution itself.
  // On the colliding rings at 20 m/s (h = 1 mm, `fragmpm run`, one thread) this takes the solves
  // that stop at the iteration limit from 126 to 24 (direct solves 149 → 24) and the iterations
  // from 21.2 to 18.5 a solve (23.8 without extrapolation), with the energies at 625 µs the same to
  // six digits.

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

#define FRAGMPM_INSTANTIATE(D)                                                  \
  template void solve_phase_field<D, ShapeFunctionKind::linear>(StepState<D>&); \
  template void solve_phase_field<D, ShapeFunctionKind::ugimp>(StepState<D>&);  \
  template void solve_phase_field<D, ShapeFunctionKind::cpdi>(StepState<D>&);   \
  template void solve_phase_field<D, ShapeFunctionKind::bspline2>(StepState<D>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
