#pragma once
// What the phase-field stage keeps between steps: the per-material coefficients of the nodal
// equation, the unknowns of the active grid (one per node and body), the assembled system and the
// conjugate-gradient solver with its crack-block preconditioner. Exists only when a material has
// the phase-field law.
#include <Eigen/IterativeLinearSolvers>
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/aggregation_multigrid.hpp"
#include "fragmpm/mpm/phase_field_warm_start.hpp"
#include "fragmpm/mpm/problem.hpp"
#include "step/counted_ldlt.hpp"
#include "step/crack_block_preconditioner.hpp"

namespace fragmpm::mpm {

/// Tag of StepState::material_damages for a material with the phase-field law (0: no damage,
/// 1: a damage law of damage_law.hpp).
inline constexpr char material_phase_field = 2;

/// Relative residual |K d − f| / |f| at which the conjugate gradients stop ([KT19] §4.3: tol_c =
/// 10⁻⁶).
inline constexpr double phase_field_tolerance = 1e-6;

/// When the nodal system is solved directly. Conjugate gradients preconditioned by Jacobi cost
/// nothing to set up and suffice while the history field is mild (`fragmpm bench`, 10⁵ particles:
/// about 12 iterations a step). Once cracks are open Jacobi alone does not: the history of their
/// particles reaches 10⁵ G_c/(4 l₀), and the particle quadrature leaves K only semi-definite where
/// a few particles carry more nodes than their values and gradients fix (an isolated particle's
/// 3 × 3 B-spline nodes see rank 3), so in floating point its smallest pivots are rounding noise
/// (LDLᵀ of the colliding rings' system at 450 µs, 10 546 unknowns: 11 pivots between −10⁻¹¹ and
/// −10⁻¹⁴ against diagonals up to 2.7 × 10⁴). There Jacobi took 1 177 iterations (0.21 s) and
/// an incomplete Cholesky factor 592 (0.39 s), while a sparse LDLᵀ (Eigen's SimplicialLDLT, AMD
/// order) solves the same system in 0.055 s. The conjugate gradients are therefore preconditioned
/// with an exact solve on the cracked particles' unknowns (crack_block_preconditioner.hpp), which
/// takes the rings from 400 µs on in 12-70 iterations a step (14 ms, against 58 ms for the
/// factorisation of the whole system). A solve that reaches `phase_field_iteration_limit`
/// iterations goes on only while they have cost less than a factorisation of the whole system
/// would (phase_field_solve.cpp), then stops and the step factorises it; should the next
/// step's attempt fail as well, the steps after it factorise too, in runs that double
/// (phase_field_warm_start.hpp). The history only grows, and an earlier version of this stage
/// factorised for good after the first such solve. But the hard solves come singly: in the
/// 20 m/s rings at h = 1 mm the iterations creep up from about 15 to 60-110 a step while the
/// block's smallest pivot falls, and near 439 µs one solve did not converge in 24 296
/// iterations (2 n). After a direct solve the conjugate gradients resume at 14-15 iterations: the
/// run stopped 5 of its 11 373 solves at the limit, none right after a direct solve, and took
/// 281.6 s, against 366.0 s when the first of them switched the stage to factorisations for good
/// (3 503 direct solves).
/// Tried and not kept: conjugate gradients preconditioned with an earlier step's factor of the
/// whole system (rescaled to the new diagonal, a factorisation only when they stall). On the rings
/// at 412 µs (10 502 unknowns) they needed 11 iterations one step after a factorisation and 15-20
/// three steps after, at about 2.5 ms each (two triangular solves) against a 45 ms factorisation:
/// 300 steps took 17.9 s against 17.4 s factorising every step. Nor does a supernodal
/// factorisation pay there: on the same system (248 000 non-zeros) this LDLᵀ factorises in 34 ms,
/// SuiteSparse's CHOLMOD (supernodal, OpenBLAS on 2 threads) in 35 ms with AMD and 27 ms with
/// nested dissection, whose analysis (63 ms) only pays back while the pattern holds.
/// Once a solve with the crack block needs more than `multigrid_switch_iterations`, the run's
/// later solves are preconditioned by a multigrid V-cycle instead (fragmpm/mpm/
/// aggregation_multigrid.hpp), which the fourth-order term and large cracked grids need.
/// (The limits are in fragmpm/mpm/phase_field_warm_start.hpp.)
/// Relative diagonal shift of the direct solve (phase_field_solve.cpp).
inline constexpr double phase_field_pivot_shift = 1e-12;

template <int D>
struct PhaseFieldState {
  /// Bodies a node keeps apart: each body has its own phase field ([KT19] §3.1.1, eq. (28): one
  /// per discrete field), so a crack in one grain does not diffuse into the grain it touches. A
  /// node reached by more bodies than this lets the last ones share its last unknown.
  static constexpr int slots = 4;

  using Matrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

  /// Per material (index = material id); zero for materials without the law.
  std::vector<double> local_coefficient;     ///< G_c / (4 l₀) [J/m⁴]
  std::vector<double> gradient_coefficient;  ///< G_c l₀ [J/m²]
  std::vector<double> drive_factor;          ///< 1 − k_f
  std::vector<double> residual_stiffness;    ///< k_f
  std::vector<double> fracture_energy;       ///< G_c [J/m²]
  std::vector<double> length_scale;          ///< l₀ [m]
  /// The fourth-order anisotropic term ([KT19] §2.2; D = 2 with the B-spline only): per material
  /// whether it is on and G_c l₀³ Γ_g (phase_field_anisotropy_global) [J/m⁰·m²·m = J·m].
  std::vector<char> anisotropic;
  std::vector<Eigen::Matrix3d> fourth_order;

  /// Per node and slot of the active grid: the body the slot holds (−1 = free) and its unknown.
  std::vector<std::int32_t> node_body, node_unknown;
  /// Per unknown: its node (linear index of this step's grid) and body.
  std::vector<std::int64_t> unknown_node;
  std::vector<std::int32_t> unknown_body;
  /// More bodies than `slots` reached a node this step, so the step's bodies share one field.
  bool shared_fields = false;
  /// Node offsets o ∈ [−reach, reach]^D that two nodes of one particle's stencil can have; the
  /// rows of the system are first summed per offset (`band`, unknowns × band_width), which the
  /// strip-ordered scatter fills without races, then compressed.
  int reach = 1;
  int band_width = 1;
  std::vector<double> band;
  std::vector<double> guess_weight;  ///< Σ V₀ S̄ per unknown (the guess is Σ V₀ S̄ (1 − d_p) / this)
  /// The last solve's c carried onto this step's unknowns, NaN where it had none: the warm
  /// start's `previous` once this step is solved.
  std::vector<double> carried;
  /// The system K c = f for c = 1 − d in compressed rows ([KT19] eq. (56)-(57)).
  std::vector<int> outer, inner;
  std::vector<double> values;
  std::vector<double> shifted_values;  ///< values with the direct solve's diagonal shift
  Eigen::VectorXd rhs, guess, solution;
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, CrackBlockPreconditioner> solver;
  /// The same with one multigrid V-cycle as the preconditioner (PhaseFieldWarmStart::multigrid).
  Eigen::ConjugateGradient<Matrix, Eigen::Lower | Eigen::Upper, AggregationMultigrid>
      multigrid_solver;
  /// The multigrid preconditioner holds the levels built from `last.levels_values` (false after a
  /// restart, until they are built again from it).
  bool levels_held = false;
  bool levels_kept = false;  ///< the last multigrid solve kept the levels of an earlier system
  /// The direct solve: K is symmetric, so its compressed rows are also its compressed columns.
  using ColumnMatrix = Eigen::SparseMatrix<double, Eigen::ColMajor, int>;
  CountedLdlt<ColumnMatrix> direct_solver;
  /// The pattern (compressed rows) the direct solver's ordering and elimination tree were computed
  /// for. The ordering depends on the pattern alone, so a step whose unknowns and couplings did not
  /// change factorises with it again and gets the same bits as a fresh analysis.
  std::vector<int> analysed_outer, analysed_inner;
  bool pattern_reused = false;  ///< the last direct solve skipped the analysis
  /// What one factorisation costs in conjugate-gradient iterations
  /// (factorisation_cost_in_iterations), as last weighed by a solve that reached the iteration
  /// limit (0 before).
  double factorisation_iterations = 0.0;
  /// The last solution, which starts the next solve, and how many of the next solves are direct.
  PhaseFieldWarmStart<D> last;
  /// Conjugate-gradient iterations after which a solve weighs going on against factorising.
  int iteration_limit = phase_field_iteration_limit;
  bool weigh_factorisation = true;  ///< go on past the limit while a factorisation costs more
  PhaseFieldPreconditioner preconditioner = PhaseFieldPreconditioner::automatic;
  bool went_past_limit = false;   ///< the last solve went past it and converged iteratively
  bool direct = false;            ///< the last solve factorised K (sparse LDLᵀ)
  bool multigrid = false;         ///< its conjugate gradients were preconditioned by multigrid
  bool stopped_at_limit = false;  ///< its conjugate gradients stopped at the iteration limit
  int iterations = 0;             ///< of the last solve
  /// Per particle, g(d) before the last solve less g(d) after it (0 for other materials): the
  /// step's constitutive update books (g_old − g_new)(H − ψ⁺) as the history excess.
  std::vector<double> degradation_drop;
  double residual = 0.0;  ///< relative residual of the last solve
};

}  // namespace fragmpm::mpm
