#pragma once
// What a phase-field run carries from one nodal solve to the next ([KT19] Alg. 1 solves the
// phase-field system once a step): the last solution c = 1 − d per grid node and field and the
// one before it, which start the next conjugate-gradient solve, and how many of the next solves
// are direct. A checkpoint stores it, so a restarted run repeats the uninterrupted one bit for bit.
#include <algorithm>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Conjugate-gradient iterations after which a phase-field solve weighs stopping and factorising
/// the whole system instead (why: step/phase_field_state.hpp): it goes on while the iterations
/// so far cost less than one factorisation (factorisation_cost_in_iterations), and stops at the
/// larger of the two counts.
inline constexpr int phase_field_iteration_limit = 300;
/// Conjugate-gradient iterations that cost as much as one sparse LDLᵀ factorisation of the same
/// system, in multiply-adds. Factorising by columns, column j of L with c_j entries below the
/// diagonal updates the c_j (c_j + 1)/2 entries of the trailing matrix that it reaches, about
/// Σ_j c_j²/2 in all (`squared_column_counts` = Σ_j c_j², from the symbolic analysis alone). One
/// preconditioned iteration multiplies by K (nnz(K)), takes two dot products and three vector
/// updates and scales by the diagonal (6 n), and solves with the crack block's factor (a forward
/// and a backward substitution, 2 nnz(L_C)). On the orthotropic plate's system at h = 0.125 mm
/// (259 369 unknowns, nnz(K) = 6.45 × 10⁶, Σ c_j² = 1.77 × 10¹⁰) this gives 1 107; timed on one
/// thread, the factorisation (7.7 s) took as long as about 1 390 Jacobi iterations, so the count
/// errs towards factorising early.
/// With the multigrid preconditioner (step/aggregation_multigrid.hpp) an iteration applies a
/// V-cycle instead of the block's substitutions: `preconditioner_multiply_adds` is what one
/// application costs (2 nnz(L_C) for the crack block).
inline double factorisation_cost_in_iterations(double squared_column_counts, double nonzeros,
                                               double unknowns,
                                               double preconditioner_multiply_adds) {
  return 0.5 * squared_column_counts / (nonzeros + 6.0 * unknowns + preconditioner_multiply_adds);
}

/// Average iterations of the crack-block solves above which the next solves are preconditioned by
/// multigrid instead (step/aggregation_multigrid.hpp). A multigrid solve costs as much as many
/// crack-block iterations: on the cubic plate's system at h = 0.125 mm after it branched (259 369
/// unknowns, one thread) about 135 (0.5 s to build the levels and 35 V-cycles of about 40 ms,
/// against iterations of about 14 ms; the crack block needed 408), and on the bench's cracked
/// cubic block (25 000 unknowns) the two cost the same where the crack block needs about 135.
/// What counts is the average, not one solve: in the colliding rings (10 000-12 000 unknowns) the
/// crack block takes 15-25 iterations a solve, with rare solves that creep past 100 or stall;
/// when the first solve past 100 switched the run for good, `verify two-rings --quick` at 10 m/s
/// took 515 s instead of 220 s, with the same pieces and crack energies.
inline constexpr int multigrid_switch_iterations = 150;
/// Solves over which the average above is taken: each crack-block solve moves it by 1/this of the
/// difference (an exponential average, so that it needs one number in a checkpoint).
inline constexpr double multigrid_average_solves = 20.0;

/// The average after a crack-block solve of `iterations`, and whether the next solves switch to
/// multigrid.
inline bool average_iterations_call_for_multigrid(double& average, int iterations) {
  average += (static_cast<double>(iterations) - average) / multigrid_average_solves;
  return average > static_cast<double>(multigrid_switch_iterations);
}

/// Which preconditioner the phase-field conjugate gradients use: `automatic` (the crack block
/// until a solve needs more than multigrid_switch_iterations, then multigrid), or either one
/// throughout, as the bench and the tests compare them.
enum class PhaseFieldPreconditioner { automatic, crack_block, multigrid };

/// Direct solves from a conjugate-gradient solve that stops at its iteration limit (that step's
/// own included) to the next attempt: the first time, and at most, doubling while the attempts
/// keep failing. One is enough in the runs measured: the failures come singly, and the conjugate
/// gradients converge again from the exact solution of one factorisation (the 20 m/s rings at
/// h = 1 mm: 5 failures in 11 373 solves, none right after a direct solve;
/// step/phase_field_state.hpp). Should they keep failing, the doubling bounds what the attempts
/// cost: each stops after the limit's 300 iterations, on those rings' 12 000 unknowns about two
/// factorisations of the whole system (a profile puts 0.35 ms of CPU time in an iteration, a
/// factorisation takes about 45 ms), so after k failures in a row the 2ᵏ − 1 direct solves carry
/// about 2k factorisations' worth of failed attempts, a few per cent once k reaches 8.
inline constexpr std::int32_t first_direct_run = 1;
inline constexpr std::int32_t longest_direct_run = 4096;

/// Solves that may use the multigrid levels built from one system (aggregation_multigrid.hpp)
/// before they are built afresh. Building them (λ_max by Lanczos, the smoothed prolongators, the
/// Galerkin products, the coarsest factorisation) took 23 of the 86 ms of the bench's cubic
/// phase-field stage a step on one thread, more than two solves' V-cycles; a step changes the
/// system little (H grows by one step's strain, the particles move a fraction of a cell), and
/// levels kept from the system 20 steps back needed the same 11.3 V-cycles a solve there.
inline constexpr std::int32_t multigrid_reuse_solves = 20;
/// A solve with kept levels that needs more than this many times the V-cycles of the first
/// solve with them, plus one, has the next solve build them afresh: the system has moved away
/// from the one they were built for (a crack growing through the coarse cells).
inline constexpr double multigrid_reuse_cycle_growth = 1.25;

/// Whether the next multigrid solve keeps the levels of `last` (the warm start after the last
/// solve), on unknowns that are the last solve's (`same_unknowns`).
template <typename WarmStart>
bool keep_multigrid_levels(const WarmStart& last, bool same_unknowns) {
  return same_unknowns && !last.levels_values.empty() && last.levels_age < multigrid_reuse_solves &&
         static_cast<double>(last.last_cycles) <=
             multigrid_reuse_cycle_growth * static_cast<double>(last.levels_cycles) + 1.0;
}

template <int D>
struct PhaseFieldWarmStart {
  std::vector<IVec<D>> node;        ///< global grid node of each unknown
  std::vector<std::int32_t> field;  ///< its field (body, or 0 when the bodies shared one)
  std::vector<double> solution;     ///< c = 1 − d at the node
  /// c at the same node and field one solve earlier, NaN where that solve had no such unknown
  /// and everywhere when the last solve was direct; empty for checkpoints written before it was
  /// kept. The next solve starts from the linear extrapolation 2 c − c_previous where it is finite
  /// (step/phase_field_solve.cpp).
  std::vector<double> previous;
  /// Solves left that factorise the whole system before conjugate gradients are tried again
  /// (0: the next solve iterates), and the length of the run of direct solves they belong to,
  /// counting the solve that stopped at the limit (0: the last conjugate-gradient solve
  /// converged within its iteration limit).
  std::int32_t direct_solves_left = 0;
  std::int32_t direct_run = 0;
  /// Whether the next solves are preconditioned by multigrid: set once the crack-block solves'
  /// average iterations pass `multigrid_switch_iterations`, and kept.
  std::int32_t multigrid = 0;
  /// That average so far (average_iterations_call_for_multigrid).
  double average_iterations = 0.0;
  /// The system (compressed rows over the last solve's unknowns) that the multigrid levels of the
  /// last solve were built from, empty when the last solve did not iterate with multigrid: a
  /// restarted run builds the same levels from it and goes on as the uninterrupted run does.
  std::vector<int> levels_outer, levels_inner;
  std::vector<double> levels_values;
  /// Solves that have used those levels (the one that built them included), the V-cycles of the
  /// first of them and of the last (keep_multigrid_levels).
  std::int32_t levels_age = 0;
  std::int32_t levels_cycles = 0;
  std::int32_t last_cycles = 0;

  bool empty() const { return solution.empty(); }
};

/// After a solve that reached the iteration limit (and is finished directly): the run of direct
/// solves it begins, twice the last one when the attempt right after that failed as well.
template <int D>
void begin_direct_run(PhaseFieldWarmStart<D>& next) {
  next.direct_run =
      next.direct_run > 0 ? std::min(2 * next.direct_run, longest_direct_run) : first_direct_run;
  next.direct_solves_left = next.direct_run - 1;
}

}  // namespace fragmpm::mpm
