#include "fragmpm/analysis/particle_domain.hpp"

#include <cmath>

namespace fragmpm::analysis {

namespace {
double domain_area(const mpm::Mat<2>& r) {
  return std::abs(r(0, 0) * r(1, 1) - r(1, 0) * r(0, 1));
}
}  // namespace

double particle_area(const mpm::Particles<2>& P, std::size_t p) {
  const double v = P.volume0[p] * P.F[p].determinant();
  return v > 0.0 ? v : domain_area(P.domain[p]);
}

double particle_spacing(const mpm::Particles<2>& P, std::size_t p) {
  return std::sqrt(particle_area(P, p));
}

std::array<mpm::Vec<2>, 4> particle_corners(const mpm::Particles<2>& P, std::size_t p) {
  mpm::Vec<2> r1 = P.domain[p].col(0);
  mpm::Vec<2> r2 = P.domain[p].col(1);
  if (domain_area(P.domain[p]) <= 0.0) {
    const double s = particle_spacing(P, p);
    r1 = {s, 0.0};
    r2 = {0.0, s};
  }
  const mpm::Vec<2>& x = P.x[p];
  // Counter-clockwise when r1 × r2 > 0 (and clockwise otherwise: still a convex quadrilateral).
  return {x - 0.5 * r1 - 0.5 * r2, x + 0.5 * r1 - 0.5 * r2, x + 0.5 * r1 + 0.5 * r2,
          x - 0.5 * r1 + 0.5 * r2};
}

}  // namespace fragmpm::analysis
