#pragma once
// The CPDI domain of a failed particle, kept within one cell.
#include <algorithm>
#include <cmath>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Failed particles keep their CPDI domain within one cell: the longest diagonal is scaled down to
/// h ([HH17] §2.6), so a fully damaged particle cannot smear across the crack it opened.
template <int D>
void limit_failed_domain(Mat<D>& domain, double cell_size) {
  double longest2 = 0.0;
  for (int signs = 0; signs < (1 << (D - 1)); ++signs) {
    Vec<D> diagonal = domain.col(0);
    for (int k = 1; k < D; ++k) diagonal += ((signs >> (k - 1)) & 1 ? -1.0 : 1.0) * domain.col(k);
    longest2 = std::max(longest2, diagonal.squaredNorm());
  }
  const double limit2 = cell_size * cell_size;
  if (longest2 > limit2) domain *= std::sqrt(limit2 / longest2);
}

}  // namespace fragmpm::mpm
