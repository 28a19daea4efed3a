#pragma once
// The CPDI domain of a failed particle: square when the particle has become a fluid, and kept
// within one cell.
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

/// The CPDI domain of a failed particle that has become a fluid: the square (cube) of its current
/// volume V₀ J, axis-aligned. At d = 1 the volumetric-deviatoric split and the isotropic
/// degradation keep no deviatoric stress, so the stress depends on J alone
/// (degrade_with_energy) and the particle's shape carries none. Sheared with F, its domain
/// became a sliver: in the three-grain column at 80 m/s and h = 0.1 mm, a failed particle in the
/// corner under the platen reached F = [0.20 0.10; −5.72 −3.43]. Its edges were 5.7 and 3.4
/// particle sizes long and 2° apart, and the one-cell limit cut its area by the square of its
/// stretch. Its shape-function gradients (∝ 1/width) made one step's velocity gradient invert it
/// (J = −0.12 at 16.5 µs). A square of the particle's own volume keeps its mass where its volume
/// is and its gradients of order 1/h.
template <int D>
Mat<D> fluid_domain(double volume) {
  return std::pow(volume, 1.0 / D) * Mat<D>::Identity();
}

/// The CPDI domain of a failed particle after its update: the square of its current `volume` if
/// its material makes it a fluid, then kept within one cell.
template <int D>
void settle_failed_domain(Mat<D>& domain, double volume, bool fluid, double cell_size) {
  if (fluid) domain = fluid_domain<D>(volume);
  limit_failed_domain<D>(domain, cell_size);
}

}  // namespace fragmpm::mpm
