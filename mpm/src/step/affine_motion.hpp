#pragma once
// What a particle's affine velocity field v(x) = v_p + C_p (x − x_p) ([JSS15]) adds to its kinetic
// energy and angular momentum, integrated over the particle's domain as a uniform parallelogram
// (parallelepiped in 3D) with edge vectors r_k: the second moment per unit mass is
// Q_p = Σ_k r_k r_kᵀ / 12, so ½ m tr(C Q Cᵀ) and m ε:(C Q) are the energy and the spin.
#include "fragmpm/mpm/current_domain.hpp"
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::mpm {

/// Q_p [m²] of the current domain (current_domain.hpp).
template <int D>
inline Mat<D> domain_second_moment(const Particles<D>& P, std::size_t p, ShapeFunctionKind kind) {
  const Mat<D> edges = current_domain<D>(P, p, kind);
  return edges * edges.transpose() / 12.0;
}

/// ½ m tr(C Q Cᵀ) [J per unit thickness in 2D].
template <int D>
inline double affine_kinetic_energy(double mass, const Mat<D>& affine, const Mat<D>& moment) {
  return 0.5 * mass * (affine * moment * affine.transpose()).trace();
}

}  // namespace fragmpm::mpm
