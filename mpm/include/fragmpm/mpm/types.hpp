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

}  // namespace fragmpm::mpm
