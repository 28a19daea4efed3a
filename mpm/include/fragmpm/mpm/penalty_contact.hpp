#pragma once
// Penalty contact of a particle with a rigid plane ([XLS21] Remark 1, eq. (83), (86)-(87)): the
// contact pressure is κ_n times the penetration depth, p = κ_n δ_n (eq. (83)), integrated over the
// particle's boundary that faces the plane. The grid walls (step/walls.cpp) act on nodes, so they
// cannot tell a particle a fraction of a cell above the plane from one touching it; this one
// measures the gap of each particle's own domain, which is what [XLS21] §4.1 uses for the Hertz
// benchmark.
#include <algorithm>
#include <cmath>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Fraction of the unit cube [0, 1]^D with a·u ≤ c. Inclusion-exclusion over the corners:
/// Σ_v (−1)^|v| max(0, c − a·v)^m / (m! Π a_k) over the m components of a that are not zero
/// (after flipping negative ones, u_k → 1 − u_k); a component below 1e-9 of |a|₁ leaves the
/// constraint independent of u_k and drops out.
template <int D>
double unit_cube_fraction_below(Vec<D> a, double c) {
  double scale = 0.0;
  for (int k = 0; k < D; ++k) scale += std::abs(a[k]);
  for (int k = 0; k < D; ++k)
    if (a[k] < 0.0) {
      c -= a[k];
      a[k] = -a[k];
    }
  int active[D];
  int m = 0;
  for (int k = 0; k < D; ++k)
    if (a[k] > 1e-9 * scale) active[m++] = k;
  if (m == 0) return c >= 0.0 ? 1.0 : 0.0;
  if (c <= 0.0) return 0.0;
  double reach = 0.0, product = 1.0, factorial = 1.0;
  for (int j = 0; j < m; ++j) {
    reach += a[active[j]];
    product *= a[active[j]];
    factorial *= j + 1;
  }
  if (c >= reach) return 1.0;
  double sum = 0.0;
  for (int corner = 0; corner < (1 << m); ++corner) {
    double offset = c;
    int bits = 0;
    for (int j = 0; j < m; ++j)
      if (corner & (1 << j)) {
        offset -= a[active[j]];
        ++bits;
      }
    if (offset > 0.0) sum += ((bits % 2) ? -1.0 : 1.0) * std::pow(offset, m);
  }
  return std::clamp(sum / (factorial * product), 0.0, 1.0);
}

/// Measure of the part of a particle's domain behind a plane [m² in 2D, m³ in 3D]: the domain is
/// the parallelogram (parallelepiped) x ± r_1/2 ± r_2/2 (columns of `domain`, as in Particles),
/// the plane passes through `point` with unit `normal` pointing to the free side. While the
/// domain is not pushed through by its own thickness this is ∫ δ_n dΓ over the face that meets the
/// plane, so κ_n × it is the force of [XLS21] eq. (86)-(87) on the particle.
template <int D>
double penetration_measure(const Vec<D>& x, const Mat<D>& domain, const Vec<D>& point,
                           const Vec<D>& normal) {
  // Quick reject: no corner can reach the plane.
  double half_reach = 0.0;
  for (int k = 0; k < D; ++k) half_reach += 0.5 * std::abs(domain.col(k).dot(normal));
  const double height = (x - point).dot(normal);
  if (height >= half_reach) return 0.0;
  // Domain = x0 + R u, u ∈ [0, 1]^D; behind the plane: (x0 + R u − point)·n ≤ 0.
  const Vec<D> origin = x - 0.5 * domain.rowwise().sum();
  const Vec<D> a = domain.transpose() * normal;
  const double c = (point - origin).dot(normal);
  return std::abs(domain.determinant()) * unit_cube_fraction_below<D>(a, c);
}

}  // namespace fragmpm::mpm
