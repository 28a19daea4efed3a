#pragma once
// The preconditioner of the phase-field system's conjugate gradients once the system is stiff: one
// V-cycle of smoothed-aggregation multigrid whose aggregates are blocks of 3^D grid nodes.
//
// Why. With Jacobi the iterations grow with the condition number of D⁻¹K, and two things make it
// large. The fourth-order anisotropic term G_c l₀³ χᵀΓχ ([KT19] eq. (4), (57)) scales as h⁻⁴
// against the local term's 1, so its smooth modes are about γ (l₀/h)⁴ times softer than its rough
// ones: the orthotropic plate at h = 0.125 mm needs 400-800 Jacobi iterations before any crack.
// An open crack's history H (10⁴-10⁸ G_c/(4 l₀)) adds rank-one terms that diagonal scaling
// cannot separate (step/crack_block_preconditioner.hpp). In both, what Jacobi leaves is smooth on
// the scale of a few cells, which a coarser grid represents: on the cubic plate's system after it
// branched (259 369 unknowns, 6.45 × 10⁶ entries) the crack block with Jacobi needs 546
// iterations from the extrapolated start, this preconditioner 43.
//
// How. Level l + 1 has one unknown per aggregate of level l: the unknowns of one field whose node
// coordinates agree after division by `multigrid_aggregate_width`. The tentative prolongator T
// (1 from each unknown to its aggregate: the constants, near the null space of the Laplacian and
// bilaplacian terms) is smoothed once by damped Jacobi, P = (I − ω D⁻¹A) T with
// ω = 4/(3 λ_max(D⁻¹A)), so that neighbouring columns overlap and the coarse correction follows
// smooth errors rather than steps from aggregate to aggregate; the coarse matrix is the Galerkin
// product A_c = Pᵀ A P, symmetric positive (semi-)definite as A. The smoother is Chebyshev-
// accelerated Jacobi on [λ_max/30, λ_max]: a polynomial in D⁻¹A, the same before and after the
// coarse correction, so the V-cycle is a symmetric operator as conjugate gradients need, and it
// runs on matrix products, which Eigen spreads over threads by rows. The coarsest level (at most
// `multigrid_coarsest_unknowns`) is factorised. The phase-field stage keeps a hierarchy for up to
// `multigrid_reuse_solves` steps while the unknowns stay the same (`reuse_levels`: the finest
// level then smooths with the new system and its diagonal, only the coarse correction is the
// older system's), and its checkpoints carry the system the hierarchy was built from, so that a
// restarted run builds the same levels and repeats the uninterrupted run bit for bit.
//
// Limits. Constants are the only coarse modes, and the bilaplacian also keeps linear functions
// near its null space: where the fourth-order term dominates, the V-cycles grow with refinement,
// about 2× per halving of h at fixed l₀ (Jacobi: 4×; tests/mpm/test_aggregation_multigrid.cpp).
// Adding the linear modes to T (three coarse unknowns per aggregate in 2D, orthonormalised per
// aggregate) was measured and left out: 60 / 122 → 13 / 33 cycles on the model, 11.3 → 6.4 on the
// bench's cubic block, but the stage 86 → 192 ms a step there, the denser coarse levels costing
// more to build and to cycle through than the cycles they save (docs/design.md).
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <array>
#include <cstdint>
#include <vector>

namespace fragmpm::mpm {

/// Nodes per direction of an aggregate.
/// 3 rather than the usual 2: on the cubic plate's branched system (one thread) width 2 took 15-18
/// V-cycles but 1.5-1.7 s to build its five levels (operator complexity 2.0: the smoothed
/// prolongator widens the B-spline's 5-node stencil, and each level's stencil grows); width 3
/// took 35-43 V-cycles of about half the cost after 0.5 s to build four (complexity 1.12), 1.9-2.3
/// s a solve against 2.5-3.1 s. With the levels kept over steps the build no longer decides it:
/// on the bench's cubic block width 2 took 5.0 V-cycles a solve against 11.3, but the stage 61.9
/// and 42.7 ms a step (one and two threads) against 59.6 and 39.4 ms, its denser cycles costing
/// what the fewer save.
inline constexpr int multigrid_aggregate_width = 3;
/// Unknowns at or below which a level is factorised instead of coarsened further.
inline constexpr int multigrid_coarsest_unknowns = 2000;
/// Degree of the Chebyshev smoother before and after each coarse correction. On the cubic plate's
/// branched system, degree 1 (damped Jacobi) took 15 V-cycles and degree 2 took 14: the second
/// matrix product a sweep is not repaid.
inline constexpr int multigrid_smoothing_degree = 1;
/// λ_max / λ_min of the part of the spectrum the smoother damps ([λ_max/30, λ_max]).
inline constexpr double multigrid_smoothing_range = 30.0;
/// Lanczos steps that estimate λ_max(D⁻¹A) on each level (aggregation_multigrid.cpp). Each is a
/// product with the level's matrix, so on the finest level they cost about a third of the solve's
/// own. Their largest Ritz value after 8 / 12 / 16 / 40 steps: 2.84 / 3.016 / 3.028 / 3.028 on
/// the bench's cubic block (25 600 unknowns), 3.013 / 3.108 / 3.148 / 3.192 on the bilaplacian
/// model of the tests at 129² nodes, whose largest eigenvalue Gershgorin bounds at 3.34: with the
/// 10 % margin 12 steps stay above λ_max with room, where 20 cost two thirds more.
inline constexpr int multigrid_lanczos_steps = 12;

class AggregationMultigrid {
 public:
  using Scalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };
  using RowMatrix = Eigen::SparseMatrix<double, Eigen::RowMajor, int>;

  /// Per unknown of the next system: its grid node's integer coordinates (unused directions 0)
  /// and its field. Set before the solver's compute().
  std::vector<std::array<std::int64_t, 3>> coordinates;
  std::vector<std::int32_t> fields;
  /// Whether the next compute() keeps the levels of the last build: the finest level then takes
  /// the new system's matrix and diagonal (same unknowns), the coarser levels, the transfers and
  /// λ_max stay those of the system they were built from.
  bool reuse_levels = false;

  Eigen::Index rows() const { return fine_rows_; }
  Eigen::Index cols() const { return fine_rows_; }

  template <typename MatrixType>
  AggregationMultigrid& analyzePattern(const MatrixType&) {
    return *this;
  }
  template <typename MatrixType>
  AggregationMultigrid& factorize(const MatrixType& matrix) {
    return compute(matrix);
  }
  /// Builds the hierarchy of `matrix` (compressed rows, symmetric, both triangles stored); the
  /// matrix must outlive the solves.
  template <typename MatrixType>
  AggregationMultigrid& compute(const MatrixType& matrix) {
    build(matrix.rows(), matrix.nonZeros(), matrix.outerIndexPtr(), matrix.innerIndexPtr(),
          matrix.valuePtr());
    return *this;
  }

  /// z = one V-cycle applied to r.
  const Eigen::VectorXd& solve(const Eigen::VectorXd& residual) const;

  Eigen::ComputationInfo info() const { return Eigen::Success; }

  /// Levels of the last hierarchy (1: the system was small enough to factorise).
  int levels() const { return static_cast<int>(levels_.size()); }
  /// Σ nnz over the levels / nnz of the system.
  double operator_complexity() const;
  /// Multiply-adds of one V-cycle: per level two products with its matrix (the residual and the
  /// smoothing after the coarse correction), one with each transfer and the vector work, and the
  /// coarsest level's two substitutions.
  double multiply_adds() const;

 private:
  struct Level {
    RowMatrix matrix;  ///< the Galerkin product (empty on the finest level, which is the system)
    RowMatrix prolongation, restriction;  ///< to and from the next level
    Eigen::VectorXd inverse_diagonal;
    double largest_eigenvalue = 1.0;  ///< λ_max(D⁻¹A), estimated from above
    std::vector<std::array<std::int64_t, 3>> coordinates;
    std::vector<std::int32_t> fields;
    mutable Eigen::VectorXd solution, rhs, residual, direction;
  };
  using RowMap = Eigen::Map<const RowMatrix>;

  void build(Eigen::Index rows, Eigen::Index nonzeros, const int* outer, const int* inner,
             const double* values);
  RowMap matrix(std::size_t level) const;
  void smooth(std::size_t level, bool from_zero) const;
  void cycle(std::size_t level) const;

  Eigen::Index fine_rows_ = 0, fine_nonzeros_ = 0;
  const int* fine_outer_ = nullptr;
  const int* fine_inner_ = nullptr;
  const double* fine_values_ = nullptr;
  std::vector<Level> levels_;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double, Eigen::ColMajor, int>, Eigen::Lower,
                        Eigen::AMDOrdering<int>>
      coarsest_;
};

}  // namespace fragmpm::mpm
