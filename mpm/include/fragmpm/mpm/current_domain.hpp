#pragma once
// The particle's domain in the current configuration, for every kernel. CPDI carries the deformed
// domain in Particles::domain and moves its corners with the grid; the other kernels never read a
// deformed domain (uGIMP keeps the initial size by definition, linear and B-spline weights see
// only x_p), so their Particles::domain stays the initial one and F maps it to the material's
// current shape. Anything that draws or measures a particle's extent (figures, fragment shape,
// the APIC second moment) must use this, or a rotated piece of a non-CPDI run keeps its squares
// axis-aligned: gaps and overlaps inside a rigid body that has turned.
#include <cstddef>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::mpm {

/// Edge vectors of particle p's current domain [m] (columns).
template <int D>
inline Mat<D> current_domain(const Particles<D>& P, std::size_t p, ShapeFunctionKind kind) {
  if (kind == ShapeFunctionKind::cpdi) return P.domain[p];
  return P.F[p] * P.domain[p];
}

/// A copy of the particles whose domains are the current ones (what a frame of the run file holds).
template <int D>
inline Particles<D> with_current_domains(Particles<D> particles, ShapeFunctionKind kind) {
  if (kind != ShapeFunctionKind::cpdi)
    for (std::size_t p = 0; p < particles.size(); ++p)
      particles.domain[p] = current_domain<D>(particles, p, kind);
  return particles;
}

}  // namespace fragmpm::mpm
