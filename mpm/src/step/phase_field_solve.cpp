// Step 5 of the phase-field stage: the solve of K c = f and the warm start of the next one.
#include <algorithm>
#include <cmath>
#include <limits>

#include "step/phase_field_parts.hpp"

namespace fragmpm::mpm {

template <int D>
void solve_phase_field_system(StepState<D>& state) {
  PhaseFieldState<D>& pf = *state.phase_field;
  constexpr int K = PhaseFieldState<D>::slots;
  const GridIndex<D>& grid = state.grid;
  const std::size_t m = pf.unknown_node.size();
  const std::int64_t unknowns = static_cast<std::int64_t>(m);
  const std::size_t nonzeros = static_cast<std::size_t>(pf.outer[m]);

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
}

template void solve_phase_field_system<2>(StepState<2>&);
template void solve_phase_field_system<3>(StepState<3>&);

}  // namespace fragmpm::mpm
