#pragma once
// Small fixed-size tensor types shared by the whole core. D is the spatial dimension (2 = plane
// strain).
#include <Eigen/Dense>
#include <cstdint>

namespace fragmpm::mpm {

template <int D>
using Vec = Eigen::Matrix<double, D, 1>;
template <int D>
using Mat = Eigen::Matrix<double, D, D>;
template <int D>
using IVec = Eigen::Matrix<std::int64_t, D, 1>;

/// Axial vectors (angular momentum, torque): the out-of-plane component alone in 2D, three
/// components in 3D.
template <int D>
using Axial = Eigen::Matrix<double, D == 2 ? 1 : 3, 1>;

/// a × b.
template <int D>
inline Axial<D> cross(const Vec<D>& a, const Vec<D>& b) {
  if constexpr (D == 2)
    return Axial<2>(a[0] * b[1] - a[1] * b[0]);
  else
    return a.cross(b);
}

/// The axial vector of the skew part of M, ε_kij M_ji: the angular momentum density Σ r × (M r)
/// of a velocity field v = M r over a mass distribution whose second moment Q gives M = C Q.
template <int D>
inline Axial<D> axial(const Mat<D>& M) {
  if constexpr (D == 2)
    return Axial<2>(M(1, 0) - M(0, 1));
  else
    return Axial<3>(M(2, 1) - M(1, 2), M(0, 2) - M(2, 0), M(1, 0) - M(0, 1));
}

}  // namespace fragmpm::mpm
