#pragma once
// Eigen's sparse LDLᵀ (AMD order), with what its symbolic analysis knows about the factor: the
// entries of each column of L below the diagonal, from which the phase-field stage weighs a
// factorisation against more conjugate-gradient iterations (factorisation_cost_in_iterations).
#include <Eigen/SparseCholesky>

namespace fragmpm::mpm {

template <typename Matrix>
class CountedLdlt : public Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> {
 public:
  /// Σ_j c_j² over the column counts of L (valid after analyzePattern).
  double squared_column_counts() const {
    double sum = 0.0;
    for (Eigen::Index j = 0; j < this->m_nonZerosPerCol.size(); ++j) {
      const double count = static_cast<double>(this->m_nonZerosPerCol[j]);
      sum += count * count;
    }
    return sum;
  }
  /// Σ_j c_j: the entries of L below the diagonal (valid after analyzePattern).
  double factor_nonzeros() const {
    double sum = 0.0;
    for (Eigen::Index j = 0; j < this->m_nonZerosPerCol.size(); ++j)
      sum += static_cast<double>(this->m_nonZerosPerCol[j]);
    return sum;
  }
};

}  // namespace fragmpm::mpm
