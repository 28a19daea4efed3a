#pragma once
// The preconditioner of the phase-field system's conjugate gradients once cracks are open: an
// exact (sparse LDLᵀ) solve on the unknowns that cracked particles reach, Jacobi on the rest.
//
// Why. K = Σ_p V_p [(G_c/(4 l₀) + H_p) S̄_p S̄_pᵀ + G_c l₀ ∇S̄_p ∇S̄_pᵀ]. Where a particle's
// history H_p is r = H_p / (G_c/(4 l₀)) times the local coefficient, its rank-one term S̄_p S̄_pᵀ is
// r times everything else in those rows, but it stiffens only the one combination S̄_pᵀ c of the
// 3 × 3 nodes it reaches. The node values that leave the cracked particles' S̄_pᵀ c unchanged keep
// the small G_c/(4 l₀) and Laplacian entries, so K has eigenvalues of order r and of order 1 in
// the same rows, and no diagonal scaling separates them: the scaled condition number grows with r
// (10⁴-10⁸ in an open crack), and Jacobi-preconditioned conjugate gradients need hundreds to
// thousands of iterations (phase_field_state.hpp). Lumping the history term onto the diagonal
// would bound the condition number, but it pins every node a cracked particle reaches to c ≈ 0,
// a crack about two cells wide: the imposed crack of `phase-field-bar` then holds 1.19 G_c per
// length at h = l₀/2 instead of 1.04. Solving the stiff unknowns exactly keeps the consistent
// system and removes the r-dependence: with P the block diagonal of K_CC (C the unknowns some
// particle with r > stiff_history_ratio reaches) and diag(K_RR), P⁻¹K is the identity on C plus
// the C-R coupling of the bounded terms, whose condition does not depend on r. P is symmetric
// positive definite (K_CC is, with its relative pivot shift below), as conjugate
// gradients need. C is the cracks' neighbourhood, a small part of the unknowns, so its
// factorisation costs a fraction of the whole system's.
#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>
#include <cstdint>
#include <vector>

#include "step/counted_ldlt.hpp"

namespace fragmpm::mpm {

/// History ratio H / (G_c/(4 l₀)) above which a particle's nodes join the exactly solved block
/// (c ≲ 1 % at the particle). Below it Jacobi copes: on the colliding rings' system at 450 µs
/// (10 498 unknowns) the block of ratio 10² (662 unknowns) cut Jacobi's 2 706 iterations to 947,
/// of ratio 10 (776) to 441; with the warm start of a running step it takes 12-70 (below).
inline constexpr double stiff_history_ratio = 1e2;
/// Relative diagonal shift of the block's factorisation. K_CC inherits K's directions that no
/// particle sees (phase_field_state.hpp); P⁻¹ multiplies the rounding-level residual in them by
/// 1/shift, and the warm start carries the result from step to step, where nothing pulls it back.
/// With the direct solve's 10⁻¹² the largest nodal |c| of the rings grew by 10 % a step and the
/// run failed within 100 steps; at 10⁻⁸ and 10⁻⁶ it stays where Jacobi leaves it and the run
/// matches Jacobi's to the printed digits.
inline constexpr double crack_block_pivot_shift = 1e-8;

class CrackBlockPreconditioner {
 public:
  using Scalar = double;
  using StorageIndex = int;
  enum { ColsAtCompileTime = Eigen::Dynamic, MaxColsAtCompileTime = Eigen::Dynamic };

  /// Per unknown of the next system: whether it belongs to the exactly solved block. Set before
  /// the solver's compute(); an empty or all-zero mark gives plain Jacobi.
  std::vector<char> stiff;
  /// Relative diagonal shift of the block's factorisation.
  double pivot_shift = crack_block_pivot_shift;

  Eigen::Index rows() const { return static_cast<Eigen::Index>(inverse_diagonal_.size()); }
  Eigen::Index cols() const { return rows(); }
  /// Unknowns in the block at the last compute().
  std::int64_t block_size() const { return static_cast<std::int64_t>(block_unknowns_.size()); }

  template <typename MatrixType>
  CrackBlockPreconditioner& analyzePattern(const MatrixType&) {
    return *this;
  }
  template <typename MatrixType>
  CrackBlockPreconditioner& factorize(const MatrixType& matrix) {
    return compute(matrix);
  }
  template <typename MatrixType>
  CrackBlockPreconditioner& compute(const MatrixType& matrix) {
    const Eigen::Index n = matrix.rows();
    inverse_diagonal_.assign(static_cast<std::size_t>(n), 1.0);
    block_index_.assign(static_cast<std::size_t>(n), -1);
    block_unknowns_.clear();
    const bool marked = static_cast<Eigen::Index>(stiff.size()) == n;
    for (Eigen::Index i = 0; i < n; ++i)
      if (marked && stiff[static_cast<std::size_t>(i)]) {
        block_index_[static_cast<std::size_t>(i)] = static_cast<int>(block_unknowns_.size());
        block_unknowns_.push_back(static_cast<int>(i));
      }
    block_outer_.assign(block_unknowns_.size() + 1, 0);
    block_inner_.clear();
    block_values_.clear();
    // K is stored by rows and symmetric, so row i of the block is also its column i: the block's
    // lower triangle in compressed columns is each block row's entries at or after the diagonal.
    for (Eigen::Index outer = 0; outer < matrix.outerSize(); ++outer)
      for (typename MatrixType::InnerIterator it(matrix, outer); it; ++it) {
        const Eigen::Index i = it.row(), j = it.col();
        if (i == j && it.value() != 0.0)
          inverse_diagonal_[static_cast<std::size_t>(i)] = 1.0 / it.value();
      }
    for (std::size_t b = 0; b < block_unknowns_.size(); ++b) {
      const Eigen::Index i = block_unknowns_[b];
      for (typename MatrixType::InnerIterator it(matrix, i); it; ++it) {
        const int column = block_index_[static_cast<std::size_t>(it.index())];
        if (column < static_cast<int>(b)) continue;
        block_inner_.push_back(column);
        block_values_.push_back(column == static_cast<int>(b) ? it.value() * (1.0 + pivot_shift)
                                                              : it.value());
      }
      block_outer_[b + 1] = static_cast<int>(block_inner_.size());
    }
    if (block_unknowns_.empty()) return *this;
    const Eigen::Map<const Eigen::SparseMatrix<double, Eigen::ColMajor, int>> block(
        block_size(), block_size(), static_cast<Eigen::Index>(block_values_.size()),
        block_outer_.data(), block_inner_.data(), block_values_.data());
    // The AMD ordering depends on the block's pattern alone (as the whole system's,
    // phase_field_solve.cpp): a step with the last step's pattern only refactorises.
    if (analysed_outer_ != block_outer_ || analysed_inner_ != block_inner_) {
      factor_.analyzePattern(block);
      analysed_outer_ = block_outer_;
      analysed_inner_ = block_inner_;
    }
    factor_.factorize(block);
    return *this;
  }

  /// z = P⁻¹ r.
  Eigen::VectorXd solve(const Eigen::VectorXd& residual) const {
    Eigen::VectorXd z(residual.size());
    for (Eigen::Index i = 0; i < residual.size(); ++i)
      z[i] = inverse_diagonal_[static_cast<std::size_t>(i)] * residual[i];
    if (block_unknowns_.empty() || factor_.info() != Eigen::Success) return z;
    // The block's vectors are kept between iterations (sized once per compute()).
    block_residual_.resize(block_size());
    for (std::size_t b = 0; b < block_unknowns_.size(); ++b)
      block_residual_[static_cast<Eigen::Index>(b)] = residual[block_unknowns_[b]];
    block_z_ = factor_.solve(block_residual_);
    for (std::size_t b = 0; b < block_unknowns_.size(); ++b)
      z[block_unknowns_[b]] = block_z_[static_cast<Eigen::Index>(b)];
    return z;
  }

  Eigen::ComputationInfo info() const { return Eigen::Success; }
  /// Entries below the diagonal of the block's factor (0 without a block): two substitutions with
  /// it are part of every iteration's cost.
  double factor_nonzeros() const {
    return block_unknowns_.empty() ? 0.0 : factor_.factor_nonzeros();
  }

 private:
  std::vector<double> inverse_diagonal_;
  std::vector<int> block_index_;     ///< per unknown: its place in the block, or −1
  std::vector<int> block_unknowns_;  ///< per block place: the unknown
  std::vector<int> block_outer_, block_inner_;
  std::vector<double> block_values_;
  std::vector<int> analysed_outer_, analysed_inner_;
  mutable Eigen::VectorXd block_residual_, block_z_;
  CountedLdlt<Eigen::SparseMatrix<double, Eigen::ColMajor, int>> factor_;
};

}  // namespace fragmpm::mpm
