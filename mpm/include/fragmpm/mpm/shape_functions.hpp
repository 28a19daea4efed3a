#pragma once
// Particle–node weights S̄_ip and gradients ∇S̄_ip for the linear, uGIMP, CPDI and quadratic
// B-spline shape functions.
// A stencil lists (node, weight, gradient) entries; a node may appear more than once (CPDI corners
// sharing a cell), which is harmless because every use is a sum over the entries.
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "fragmpm/mpm/grid_index.hpp"
#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::mpm {

template <int D>
struct Stencil {
  /// CPDI: 2^D corners × 2^D nodes each.
  static constexpr int capacity = (1 << D) * (1 << D);
  int count = 0;
  std::array<std::int64_t, capacity> node;
  std::array<double, capacity> weight;
  std::array<Vec<D>, capacity> gradient;
  /// x_i − x_p, filled only by the stencils built with Offsets (the APIC transfer needs them).
  std::array<Vec<D>, capacity> offset;
};

namespace detail {
/// Linear hat values at the 2^D nodes of the cell holding x (unclamped; outside the active grid is
/// the caller's responsibility). Calls emit(global node, value, gradient of the hat).
template <int D, class Emit>
inline void linear_hat(const Vec<D>& x, const GridIndex<D>& grid, Emit&& emit) {
  IVec<D> base;
  Vec<D> frac;
  for (int k = 0; k < D; ++k) {
    const double s = (x[k] - grid.origin[k]) * grid.inverse_cell_size;
    const double f = std::floor(s);
    base[k] = static_cast<std::int64_t>(f);
    frac[k] = s - f;
  }
  for (int corner = 0; corner < (1 << D); ++corner) {
    IVec<D> node = base;
    double value = 1.0;
    Vec<D> gradient = Vec<D>::Zero();
    std::array<double, D> w1d{}, dw1d{};
    for (int k = 0; k < D; ++k) {
      const bool upper = (corner >> k) & 1;
      node[k] += upper;
      w1d[k] = upper ? frac[k] : 1.0 - frac[k];
      dw1d[k] = (upper ? 1.0 : -1.0) * grid.inverse_cell_size;
      value *= w1d[k];
    }
    for (int k = 0; k < D; ++k) {
      double g = dw1d[k];
      for (int j = 0; j < D; ++j)
        if (j != k) g *= w1d[j];
      gradient[k] = g;
    }
    emit(node, value, gradient);
  }
}

/// uGIMP 1D weight and derivative for distance xi = x_p − X_i, cell size h, particle half-length
/// lp.
inline void gimp_1d(double xi, double h, double lp, double& w, double& dw) {
  const double r = std::abs(xi);
  const double sign = xi < 0.0 ? -1.0 : 1.0;
  if (r < lp) {
    w = 1.0 - (xi * xi + lp * lp) / (2.0 * h * lp);
    dw = -xi / (h * lp);
  } else if (r < h - lp) {
    w = 1.0 - r / h;
    dw = -sign / h;
  } else if (r < h + lp) {
    const double t = h + lp - r;
    w = t * t / (4.0 * h * lp);
    dw = -sign * t / (2.0 * h * lp);
  } else {
    w = 0.0;
    dw = 0.0;
  }
}
/// Quadratic B-spline on a uniform grid, in cell units: for t = (x − origin)/h the three nodes
/// first = floor(t − ½), first + 1, first + 2 carry the weights
///   N₀ = ½ (3/2 − f)², N₁ = ¾ − (f − 1)², N₂ = ½ (f − ½)²,  f = t − first ∈ [½, 3/2),
/// the pieces of N(r) = ¾ − r² (|r| < ½), ½ (3/2 − |r|)² (½ ≤ |r| < 3/2) at the distances r = f,
/// f − 1, f − 2. They sum to 1 and reproduce t (Σ N_k (first + k) = first + f), and N is C¹ across
/// the knots at half cells, so the gradient does not jump when a particle crosses a cell face.
/// `weight`, `slope` (dN/dt) and `curvature` (d²N/dt²) per node, in cell units.
struct QuadraticBspline1d {
  std::int64_t first = 0;
  std::array<double, 3> weight{}, slope{}, curvature{};
};

inline QuadraticBspline1d quadratic_bspline_1d(double t) {
  QuadraticBspline1d b;
  const double start = std::floor(t - 0.5);
  b.first = static_cast<std::int64_t>(start);
  const double f = t - start;
  const double a = 1.5 - f, c = f - 1.0, e = f - 0.5;
  b.weight = {0.5 * a * a, 0.75 - c * c, 0.5 * e * e};
  b.slope = {-a, -2.0 * c, e};
  b.curvature = {1.0, -2.0, 1.0};
  return b;
}
}  // namespace detail

/// Standard linear (bilinear in 2D) shape functions at the particle position.
template <int D, bool Offsets = false>
inline void linear_stencil(const Vec<D>& x, const GridIndex<D>& grid, Stencil<D>& stencil) {
  stencil.count = 0;
  detail::linear_hat<D>(x, grid, [&](const IVec<D>& node, double value, const Vec<D>& gradient) {
    const int e = stencil.count++;
    stencil.node[e] = grid.linear(node);
    stencil.weight[e] = value;
    stencil.gradient[e] = gradient;
    if constexpr (Offsets) stencil.offset[e] = grid.position(node) - x;
  });
}

/// Undeformed GIMP: the particle is a box of half-length `half_length` per direction that does not
/// deform; S̄ is the tensor product of the 1D convolution of the hat with the box.
template <int D, bool Offsets = false>
inline void ugimp_stencil(const Vec<D>& x, const Vec<D>& half_length, const GridIndex<D>& grid,
                          Stencil<D>& stencil) {
  stencil.count = 0;
  const double h = grid.cell_size;
  IVec<D> first;
  for (int k = 0; k < D; ++k)
    first[k] = static_cast<std::int64_t>(
        std::floor((x[k] - half_length[k] - grid.origin[k]) * grid.inverse_cell_size));
  // Support is h + lp ≤ 1.5 h, so three nodes per direction cover it.
  constexpr int per_direction = 3;
  int total = 1;
  for (int k = 0; k < D; ++k) total *= per_direction;
  for (int combo = 0; combo < total; ++combo) {
    IVec<D> node;
    std::array<double, D> w1d{}, dw1d{};
    double value = 1.0;
    int rest = combo;
    for (int k = 0; k < D; ++k) {
      node[k] = first[k] + rest % per_direction;
      rest /= per_direction;
      const double xi = x[k] - (grid.origin[k] + h * static_cast<double>(node[k]));
      detail::gimp_1d(xi, h, half_length[k], w1d[k], dw1d[k]);
      value *= w1d[k];
    }
    if (value == 0.0) continue;
    Vec<D> gradient = Vec<D>::Zero();
    for (int k = 0; k < D; ++k) {
      double g = dw1d[k];
      for (int j = 0; j < D; ++j)
        if (j != k) g *= w1d[j];
      gradient[k] = g;
    }
    const int e = stencil.count++;
    stencil.node[e] = grid.linear(node);
    stencil.weight[e] = value;
    stencil.gradient[e] = gradient;
    if constexpr (Offsets) stencil.offset[e] = grid.position(node) - x;
  }
}

/// C¹ quadratic B-spline ([KT19] §4, eq. (34)-(35)): the tensor product of
/// detail::quadratic_bspline_1d over the directions, 3^D nodes. The grid is unbounded (the active
/// region is sized around the particles' stencils, see stencil_bounds), so every particle sees the
/// uniform, interior form of the basis: partition of unity and linear completeness hold everywhere,
/// with no open knot vector at a domain edge.
template <int D, bool Offsets = false>
inline void bspline2_stencil(const Vec<D>& x, const GridIndex<D>& grid, Stencil<D>& stencil) {
  std::array<detail::QuadraticBspline1d, D> axis;
  for (int k = 0; k < D; ++k)
    axis[k] = detail::quadratic_bspline_1d((x[k] - grid.origin[k]) * grid.inverse_cell_size);
  int total = 1;
  for (int k = 0; k < D; ++k) total *= 3;
  stencil.count = total;
  for (int e = 0; e < total; ++e) {
    IVec<D> node;
    std::array<int, D> local{};
    int rest = e;
    double value = 1.0;
    for (int k = 0; k < D; ++k) {
      local[k] = rest % 3;
      rest /= 3;
      node[k] = axis[k].first + local[k];
      value *= axis[k].weight[local[k]];
    }
    Vec<D> gradient;
    for (int k = 0; k < D; ++k) {
      double g = axis[k].slope[local[k]] * grid.inverse_cell_size;
      for (int j = 0; j < D; ++j)
        if (j != k) g *= axis[j].weight[local[j]];
      gradient[k] = g;
    }
    stencil.node[e] = grid.linear(node);
    stencil.weight[e] = value;
    stencil.gradient[e] = gradient;
    if constexpr (Offsets) stencil.offset[e] = grid.position(node) - x;
  }
}

/// The nodes of bspline2_stencil whose weight is not zero, in its entry order: nodes[0 … count).
/// A weight of the B-spline vanishes only at the end knot of its support (|x − x_i| = 1.5 h, where
/// the slope vanishes as well), so these are the entries that carry a weight or a gradient. For
/// the loops that only need to know which nodes a particle reaches: filling a whole stencil costs
/// mostly its stores of weights and gradients.
template <int D>
inline int bspline2_stencil_nodes(const Vec<D>& x, const GridIndex<D>& grid,
                                  std::array<std::int64_t, Stencil<D>::capacity>& nodes) {
  std::array<detail::QuadraticBspline1d, D> axis;
  for (int k = 0; k < D; ++k)
    axis[k] = detail::quadratic_bspline_1d((x[k] - grid.origin[k]) * grid.inverse_cell_size);
  int total = 1;
  for (int k = 0; k < D; ++k) total *= 3;
  int count = 0;
  for (int e = 0; e < total; ++e) {
    IVec<D> node;
    double value = 1.0;
    for (int k = 0, rest = e; k < D; ++k, rest /= 3) {
      node[k] = axis[k].first + rest % 3;
      value *= axis[k].weight[rest % 3];
    }
    if (value != 0.0) nodes[count++] = grid.linear(node);
  }
  return count;
}

/// Second derivatives ∂²S̄/∂x∂x of the quadratic B-spline stencil, in the entry order of
/// bspline2_stencil: per direction the curvature (1, −2, 1)/h² of the three pieces (constant
/// within a half-cell knot span, the basis being C¹), times the other directions' weights or
/// slopes. The fourth-order anisotropic phase field ([KT19] eq. (51), (57)) needs them.
template <int D>
inline void bspline2_hessians(const Vec<D>& x, const GridIndex<D>& grid,
                              std::array<Mat<D>, Stencil<D>::capacity>& hessian) {
  std::array<detail::QuadraticBspline1d, D> axis;
  for (int k = 0; k < D; ++k)
    axis[k] = detail::quadratic_bspline_1d((x[k] - grid.origin[k]) * grid.inverse_cell_size);
  int total = 1;
  for (int k = 0; k < D; ++k) total *= 3;
  const double h2 = grid.inverse_cell_size * grid.inverse_cell_size;
  for (int e = 0; e < total; ++e) {
    std::array<int, D> local{};
    for (int k = 0, rest = e; k < D; ++k, rest /= 3) local[k] = rest % 3;
    for (int a = 0; a < D; ++a)
      for (int b = a; b < D; ++b) {
        double value = h2;
        for (int k = 0; k < D; ++k) {
          const auto& axis_k = axis[k];
          const int n = local[k];
          if (a == b && k == a)
            value *= axis_k.curvature[n];
          else if (k == a || k == b)
            value *= axis_k.slope[n];
          else
            value *= axis_k.weight[n];
        }
        hessian[e](a, b) = hessian[e](b, a) = value;
      }
  }
}

/// χ = (∂²S̄/∂X², ∂²S̄/∂Y², ∂²S̄/∂X∂Y) of the 2D quadratic B-spline stencil at x in the reference
/// configuration, Fᵀ (∂²S̄/∂x∂x) F with F taken uniform over the stencil, in the entry order of
/// bspline2_stencil (e = i + 3 j): the curvatures the fourth-order anisotropic phase field
/// integrates ([KT19] eq. (51), (57)). The same as bspline2_hessians transformed by F, written out
/// because the phase-field assembly evaluates it for every particle and step: with
/// H = [s_x'' s_y, s_x' s_y'; s_x' s_y', s_x s_y''] / h², (Fᵀ H F)_ab = F_0a F_0b H_xx +
/// (F_0a F_1b + F_1a F_0b) H_xy + F_1a F_1b H_yy.
inline void bspline2_reference_curvatures(const Vec<2>& x, const Mat<2>& F,
                                          const GridIndex<2>& grid,
                                          std::array<Eigen::Vector3d, Stencil<2>::capacity>& chi) {
  const auto bx = detail::quadratic_bspline_1d((x[0] - grid.origin[0]) * grid.inverse_cell_size);
  const auto by = detail::quadratic_bspline_1d((x[1] - grid.origin[1]) * grid.inverse_cell_size);
  const double inverse_area = grid.inverse_cell_size * grid.inverse_cell_size;
  const Eigen::Vector3d from_xx(F(0, 0) * F(0, 0), F(0, 1) * F(0, 1), F(0, 0) * F(0, 1));
  const Eigen::Vector3d from_yy(F(1, 0) * F(1, 0), F(1, 1) * F(1, 1), F(1, 0) * F(1, 1));
  const Eigen::Vector3d from_xy(2.0 * F(0, 0) * F(1, 0), 2.0 * F(0, 1) * F(1, 1),
                                F(0, 0) * F(1, 1) + F(1, 0) * F(0, 1));
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i) {
      const double xx = inverse_area * bx.curvature[i] * by.weight[j];
      const double yy = inverse_area * bx.weight[i] * by.curvature[j];
      const double xy = inverse_area * bx.slope[i] * by.slope[j];
      chi[i + 3 * j] = xx * from_xx + yy * from_yy + xy * from_xy;
    }
}

/// CPDI ([XLS21] eq. (52)-(53); [HH17] §1.1). The domain is the parallelepiped spanned by the full
/// edge vectors r_k (columns of `domain`), corners x ± r1/2 ± r2/2. Interpolating the hat N_i
/// bilinearly between the corner values gives S̄_ip = mean_c N_i(x_c) and, by the divergence theorem
/// with the map x = x_p + Σ ξ_k r_k/2, ∇S̄_ip = Σ_c N_i(x_c) |det J| J^{-T} s_c / V with J =
/// domain/2 and s_c ∈ {±1}^D the corner's signs; |det J|/V = 2^{-D}, so the corner vector is J^{-T}
/// s_c / 2^D = domain^{-T} s_c · 2^{1-D}. In 2D this is exactly eq. (53) (its 1/(2V) times the
/// cofactor of the full edge vectors).
template <int D, bool Offsets = false>
inline void cpdi_stencil(const Vec<D>& x, const Mat<D>& domain, const GridIndex<D>& grid,
                         Stencil<D>& stencil) {
  stencil.count = 0;
  const Mat<D> inverse_transpose = domain.inverse().transpose();
  constexpr double corner_share = 1.0 / double(1 << D);
  constexpr double gradient_scale = 2.0 / double(1 << D);
  for (int corner = 0; corner < (1 << D); ++corner) {
    Vec<D> signs;
    for (int k = 0; k < D; ++k) signs[k] = ((corner >> k) & 1) ? 1.0 : -1.0;
    const Vec<D> corner_position = x + 0.5 * domain * signs;
    const Vec<D> corner_vector = gradient_scale * (inverse_transpose * signs);
    detail::linear_hat<D>(corner_position, grid,
                          [&](const IVec<D>& node, double value, const Vec<D>&) {
                            const int e = stencil.count++;
                            stencil.node[e] = grid.linear(node);
                            stencil.weight[e] = corner_share * value;
                            stencil.gradient[e] = value * corner_vector;
                            if constexpr (Offsets) stencil.offset[e] = grid.position(node) - x;
                          });
  }
}

/// Axis-aligned bounds (lower, upper) of the region a particle's stencil touches [m], in the form
/// the active region expects: the nodes of the cells holding `lower` and `upper` (plus one node of
/// padding each side, added by the caller). For the quadratic B-spline the cell holding x − h/2
/// starts at the stencil's first node floor(t − ½) and the cell holding x + h/2 ends at its last,
/// first + 2, so the three-node support is covered and keeps the one node of padding.
template <int D>
inline void stencil_bounds(ShapeFunctionKind kind, const Vec<D>& x, const Mat<D>& domain,
                           const Vec<D>& half_length, double cell_size, Vec<D>& lower,
                           Vec<D>& upper) {
  switch (kind) {
    case ShapeFunctionKind::linear:
      lower = upper = x;
      return;
    case ShapeFunctionKind::bspline2:
      lower = x - Vec<D>::Constant(0.5 * cell_size);
      upper = x + Vec<D>::Constant(0.5 * cell_size);
      return;
    case ShapeFunctionKind::ugimp:
      lower = x - half_length;
      upper = x + half_length;
      return;
    case ShapeFunctionKind::cpdi: {
      const Vec<D> reach = 0.5 * domain.cwiseAbs().rowwise().sum();
      lower = x - reach;
      upper = x + reach;
      return;
    }
  }
}

}  // namespace fragmpm::mpm
