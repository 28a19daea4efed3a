#pragma once
// The explicit DP-MPM step (docs/design.md), update-stress-last with a FLIP/PIC blend ([XLS21] eq.
// (64)-(66)).
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "fragmpm/mpm/phase_field_warm_start.hpp"
#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/mpm/series.hpp"

namespace fragmpm::mpm {

/// Why a step could not be taken. The run stops with exit code 3 and keeps the last good frame.
struct NumericalFailure {
  long long step = 0;
  double time = 0.0;
  long long particle = -1;
  std::string what;  ///< full diagnostic: which check failed and the particle's field values
};

/// Which modules run for this problem and why (logged, stored in /meta).
struct ModuleDecision {
  std::string module;
  bool active = false;
  std::string reason;
};

template <int D>
std::vector<ModuleDecision> plan_modules(const Problem<D>& problem);

/// Whether the step runs two velocity fields per node: partitioning is not off and the scene has
/// several bodies, a damage law, or asks for body partitioning.
template <int D>
bool partitioning_active(const Problem<D>& problem);

/// Largest stable explicit Δt for the current particle state: C_cfl h / (√D max_p(c_p + |v_p|))
/// with c_p = sqrt((K + 4G/3) / ρ_p), ρ_p = ρ0 / J. The √D is the multi-dimensional CFL factor of
/// multilinear hats with a lumped mass (docs/design.md gives the 1D form).  [s]
template <int D>
double stable_time_step(const Problem<D>& problem, const Particles<D>& particles, double cfl);

/// What the phase-field stage ([KT19] Alg. 1) has cost so far; all zero without a phase-field
/// material. For `fragmpm bench`, which sets it against the rest of the step.
struct PhaseFieldWork {
  long long runs = 0;         ///< one a step, and one at the start when the scene sets a history
  long long iterations = 0;   ///< conjugate-gradient iterations over all solves
  long long direct_runs = 0;  ///< solves by sparse LDLᵀ instead of conjugate gradients
  /// conjugate-gradient solves preconditioned by multigrid (the rest: by the crack block)
  long long multigrid_solves = 0;
  /// of those, the solves that kept the levels built from an earlier step's system
  long long kept_levels = 0;
  long long reused_orderings = 0;  ///< direct solves that kept the last step's ordering
  /// conjugate-gradient solves stopped at the iteration limit and finished directly (each starts
  /// a run of direct solves, phase_field_warm_start.hpp)
  long long stopped_at_limit = 0;
  /// conjugate-gradient solves that reached the iteration limit and converged further on, since a
  /// factorisation would have cost more (factorisation_cost_in_iterations)
  long long past_limit = 0;
  /// the largest cost of a factorisation in iterations that such a solve weighed
  double factorisation_iterations = 0.0;
  double seconds = 0.0;  ///< wall time in the stage: assembly, solve, interpolation [s]
};

template <int D>
class Solver {
 public:
  explicit Solver(Problem<D> problem);
  ~Solver();
  Solver(Solver&&) noexcept;
  Solver& operator=(Solver&&) noexcept;

  /// Advances one step. Returns a failure instead of throwing; the in-memory state is then not
  /// usable, and the caller keeps the last good frame on disk.
  /// `dt_cap` [s] shortens an adaptive step so that output and end times are hit exactly.
  std::optional<NumericalFailure> step(double dt_cap = std::numeric_limits<double>::infinity());

  const Problem<D>& problem() const;
  const Particles<D>& particles() const;
  Particles<D>& particles();
  double time() const;
  long long step_count() const;
  const EnergyAccumulators& accumulators() const;
  const SeriesRow<D>& last_row() const;  ///< row of the most recent step (or the initial state)
  Vec<D> wall_displacement(std::size_t wall) const;
  /// CFL limit (with C_cfl) from the current state: the adaptive Δt of the next step [s].
  double stable_dt() const;
  const PhaseFieldWork& phase_field_work() const;
  /// Conjugate-gradient iterations after which the next phase-field solves weigh going on against
  /// a factorisation (default `phase_field_iteration_limit`; no effect without a phase-field
  /// material), and whether they weigh at all: without, they stop at the limit and are finished
  /// directly. A lower limit exercises both paths on a small system, as the tests do.
  void set_phase_field_iteration_limit(int limit, bool weigh_factorisation = true);
  /// The preconditioner of the next phase-field solves (default `automatic`).
  void set_phase_field_preconditioner(PhaseFieldPreconditioner choice);

  /// The nodal phase field that starts the next solve (empty without a phase-field material or
  /// before the first solve), for a checkpoint.
  PhaseFieldWarmStart<D> phase_field_warm_start() const;

  /// Restores a checkpointed state (time, step, accumulators, particles and the phase-field warm
  /// start must come from the same problem).
  void restore(double time, long long step, const EnergyAccumulators& totals,
               Particles<D> particles, PhaseFieldWarmStart<D> phase_field = {});

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace fragmpm::mpm
