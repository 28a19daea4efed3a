// Shape-function invariants: partition of unity, zero-sum gradients (a constant field has zero
// gradient), exact gradient of a linear field, and CPDI = linear for an undeformed particle inside
// one cell (the bilinear hat averaged over a centred box equals its centre value, [XLS21] eq.
// (52)-(53)). The quadratic B-spline ([KT19] §4) has the same invariants, is the C¹ piecewise
// quadratic, and stays inside the padded active region.
#include <gtest/gtest.h>

#include <random>

#include "fragmpm/mpm/shape_functions.hpp"

using namespace fragmpm::mpm;

namespace {

GridIndex<2> test_grid() {
  GridIndex<2> g;
  g.origin = Vec<2>(-0.3, 0.1);
  g.cell_size = 0.25;
  g.inverse_cell_size = 4.0;
  g.lower = IVec<2>(-10, -10);
  g.extent = IVec<2>(40, 40);
  return g;
}

struct Sums {
  double weight = 0.0;
  Vec<2> gradient = Vec<2>::Zero();
  Vec<2> interpolated_linear = Vec<2>::Zero();  // Σ S̄ X_i (reproduces the position)
  Mat<2> gradient_of_linear = Mat<2>::Zero();   // Σ X_i ⊗ ∇S̄ (reproduces the identity)
};

Sums sum_stencil(const GridIndex<2>& g, const Stencil<2>& s) {
  Sums sums;
  for (int e = 0; e < s.count; ++e) {
    const Vec<2> X = g.position(g.global(s.node[e]));
    sums.weight += s.weight[e];
    sums.gradient += s.gradient[e];
    sums.interpolated_linear += s.weight[e] * X;
    sums.gradient_of_linear += X * s.gradient[e].transpose();
  }
  return sums;
}

void expect_invariants(const GridIndex<2>& g, const Stencil<2>& s, const Vec<2>& x) {
  const Sums sums = sum_stencil(g, s);
  EXPECT_NEAR(sums.weight, 1.0, 1e-13);
  EXPECT_NEAR(sums.gradient.norm(), 0.0, 1e-12);
  EXPECT_NEAR((sums.interpolated_linear - x).norm(), 0.0, 1e-13);
  EXPECT_NEAR((sums.gradient_of_linear - Mat<2>::Identity()).norm(), 0.0, 1e-12);
}

}  // namespace

TEST(ShapeFunctions, LinearPartitionOfUnityAndLinearCompleteness) {
  const auto g = test_grid();
  std::mt19937 rng(1);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    Stencil<2> s;
    linear_stencil<2>(x, g, s);
    EXPECT_EQ(s.count, 4);
    expect_invariants(g, s, x);
  }
}

TEST(ShapeFunctions, UgimpPartitionOfUnityAndLinearCompleteness) {
  const auto g = test_grid();
  std::mt19937 rng(2);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  for (double half : {0.25 * 0.25, 0.5 * 0.25 / 2.0, 0.25 / 6.0}) {
    for (int trial = 0; trial < 100; ++trial) {
      const Vec<2> x(u(rng), u(rng));
      Stencil<2> s;
      ugimp_stencil<2>(x, Vec<2>(half, half), g, s);
      expect_invariants(g, s, x);
    }
  }
}

TEST(ShapeFunctions, CpdiPartitionOfUnityForDeformedDomains) {
  const auto g = test_grid();
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(0.0, 2.0), d(-0.1, 0.1);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    Mat<2> domain;
    domain << 0.12 + d(rng), d(rng), d(rng), 0.12 + d(rng);  // sheared, stretched parallelogram
    Stencil<2> s;
    cpdi_stencil<2>(x, domain, g, s);
    EXPECT_EQ(s.count, 16);
    expect_invariants(g, s, x);
  }
}

TEST(ShapeFunctions, CpdiEqualsLinearForUndeformedParticleInsideOneCell) {
  const auto g = test_grid();
  const Vec<2> x = g.origin + Vec<2>(0.25 * 3.4, 0.25 * 5.6);  // well inside cell (3, 5)
  Mat<2> domain = Mat<2>::Identity() * 0.25 / 4.0;             // 4×4 particles per cell
  Stencil<2> cpdi, linear;
  cpdi_stencil<2>(x, domain, g, cpdi);
  linear_stencil<2>(x, g, linear);
  for (int e = 0; e < linear.count; ++e) {
    double weight = 0.0;
    Vec<2> gradient = Vec<2>::Zero();
    for (int c = 0; c < cpdi.count; ++c)
      if (cpdi.node[c] == linear.node[e]) {
        weight += cpdi.weight[c];
        gradient += cpdi.gradient[c];
      }
    EXPECT_NEAR(weight, linear.weight[e], 1e-14);
    EXPECT_NEAR((gradient - linear.gradient[e]).norm(), 0.0, 1e-12);
  }
}

TEST(ShapeFunctions, CpdiGradientMatchesPaperEquation53) {
  // [XLS21] eq. (53) written out with full edge vectors: corners x1 = x − r1/2 − r2/2, x2 = x +
  // r1/2 − r2/2, x3 = x + r1/2 + r2/2, x4 = x − r1/2 + r2/2.
  const auto g = test_grid();
  const Vec<2> x(0.61, 0.83);
  const Vec<2> r1(0.11, 0.03), r2(-0.02, 0.09);
  Mat<2> domain;
  domain.col(0) = r1;
  domain.col(1) = r2;
  const double V = r1[0] * r2[1] - r1[1] * r2[0];
  Stencil<2> s;
  cpdi_stencil<2>(x, domain, g, s);
  const Vec<2> corners[4] = {x - r1 / 2 - r2 / 2, x + r1 / 2 - r2 / 2, x + r1 / 2 + r2 / 2,
                             x - r1 / 2 + r2 / 2};
  auto hat = [&](const IVec<2>& node, const Vec<2>& at) {
    const Vec<2> X = g.position(node);
    return std::max(0.0, 1 - std::abs(at[0] - X[0]) / 0.25) *
           std::max(0.0, 1 - std::abs(at[1] - X[1]) / 0.25);
  };
  for (int e = 0; e < s.count; ++e) {
    const IVec<2> node = g.global(s.node[e]);
    Vec<2> gradient = Vec<2>::Zero();
    for (int c = 0; c < s.count; ++c)
      if (s.node[c] == s.node[e]) gradient += s.gradient[c];
    const double S1 = hat(node, corners[0]), S2 = hat(node, corners[1]), S3 = hat(node, corners[2]),
                 S4 = hat(node, corners[3]);
    const Vec<2> expected = ((S1 - S3) * Vec<2>(r1[1] - r2[1], r2[0] - r1[0]) +
                             (S2 - S4) * Vec<2>(r1[1] + r2[1], -r1[0] - r2[0])) /
                            (2.0 * V);
    EXPECT_NEAR((gradient - expected).norm(), 0.0, 1e-12) << "node " << node.transpose();
  }
}

TEST(ShapeFunctions, QuadraticBsplinePartitionOfUnityAndLinearCompleteness) {
  const auto g = test_grid();
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    EXPECT_EQ(s.count, 9);
    expect_invariants(g, s, x);
  }
  // On the knots themselves (node positions and cell mid-points) as well.
  for (const Vec<2>& x : {Vec<2>(g.origin + Vec<2>(0.25 * 3, 0.25 * 5)),
                          Vec<2>(g.origin + Vec<2>(0.25 * 3.5, 0.25 * 5.5))}) {
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    expect_invariants(g, s, x);
  }
}

TEST(ShapeFunctions, QuadraticBsplineIsTheC1PiecewiseQuadratic) {
  // N(r) = 3/4 − r² for |r| < 1/2, (3/2 − |r|)²/2 for 1/2 ≤ |r| < 3/2, r = (x − X_i)/h: the
  // stencil's weights and gradients are that function and its derivative, and both are continuous
  // where a particle crosses a knot (cell mid-point) or a node.
  const auto g = test_grid();
  auto N = [](double r) {
    const double a = std::abs(r);
    return a < 0.5 ? 0.75 - r * r : (a < 1.5 ? 0.5 * (1.5 - a) * (1.5 - a) : 0.0);
  };
  auto dN = [](double r) {
    const double a = std::abs(r);
    return a < 0.5 ? -2.0 * r : (a < 1.5 ? -(r > 0 ? 1.0 : -1.0) * (1.5 - a) : 0.0);
  };
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  for (int trial = 0; trial < 100; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    for (int e = 0; e < s.count; ++e) {
      const Vec<2> r = (x - g.position(g.global(s.node[e]))) / g.cell_size;
      EXPECT_NEAR(s.weight[e], N(r[0]) * N(r[1]), 1e-14);
      const Vec<2> gradient(dN(r[0]) * N(r[1]), N(r[0]) * dN(r[1]));
      EXPECT_NEAR((s.gradient[e] - gradient / g.cell_size).norm(), 0.0, 1e-12);
    }
  }
  // Either side of a knot (t = 5.5 cells) and of a node (t = 6): the node sets differ across the
  // knot, so compare the interpolants of a smooth nodal field f(X) = sin X₀ + X₁²: value and
  // gradient continuous to O(ε).
  auto interpolate = [&](const Vec<2>& x, double& value, Vec<2>& gradient) {
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    value = 0.0;
    gradient.setZero();
    for (int e = 0; e < s.count; ++e) {
      const Vec<2> X = g.position(g.global(s.node[e]));
      const double f = std::sin(X[0]) + X[1] * X[1];
      value += s.weight[e] * f;
      gradient += f * s.gradient[e];
    }
  };
  for (double t : {5.5, 6.0}) {
    const double eps = 1e-9;
    const Vec<2> below(g.origin[0] + (t - eps) * g.cell_size, 0.4);
    const Vec<2> above(g.origin[0] + (t + eps) * g.cell_size, 0.4);
    double v0, v1;
    Vec<2> g0, g1;
    interpolate(below, v0, g0);
    interpolate(above, v1, g1);
    EXPECT_NEAR(v0, v1, 1e-8) << "t = " << t;
    EXPECT_NEAR((g0 - g1).norm(), 0.0, 1e-7) << "t = " << t;
  }
}

TEST(ShapeFunctions, QuadraticBsplineStencilStaysInsideThePaddedActiveRegion) {
  // The active region is the union of the cells holding stencil_bounds' corners plus one node of
  // padding (step/active_region.cpp): every node of the three-node support must lie in it, one
  // node inside the padding.
  const auto g = test_grid();
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    Vec<2> lower, upper;
    stencil_bounds<2>(ShapeFunctionKind::bspline2, x, Mat<2>::Zero(), Vec<2>::Zero(), g.cell_size,
                      lower, upper);
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    for (int k = 0; k < 2; ++k) {
      const auto first =
          static_cast<std::int64_t>(std::floor((lower[k] - g.origin[k]) * g.inverse_cell_size));
      const auto last =
          static_cast<std::int64_t>(std::floor((upper[k] - g.origin[k]) * g.inverse_cell_size)) + 1;
      for (int e = 0; e < s.count; ++e) {
        const auto node = g.global(s.node[e])[k];
        EXPECT_GE(node, first);
        EXPECT_LE(node, last);
      }
    }
  }
}

TEST(ShapeFunctions, EveryKernelConservesMassAndMomentumInParticleToGrid) {
  // m_i = Σ S̄_ip m_p and p_i = Σ S̄_ip m_p v_p sum over the nodes to the particles' mass and
  // momentum because Σ_i S̄_ip = 1 for each kind.
  const auto g = test_grid();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.2, 1.8), s(-1, 1);
  for (const ShapeFunctionKind kind : {ShapeFunctionKind::linear, ShapeFunctionKind::ugimp,
                                       ShapeFunctionKind::cpdi, ShapeFunctionKind::bspline2}) {
    std::vector<double> node_mass(static_cast<std::size_t>(g.node_count()), 0.0);
    std::vector<Vec<2>> node_momentum(node_mass.size(), Vec<2>::Zero());
    double mass = 0.0;
    Vec<2> momentum = Vec<2>::Zero();
    for (int p = 0; p < 500; ++p) {
      const Vec<2> x(u(rng), u(rng)), v(s(rng), s(rng));
      const double m = 1.0 + 0.5 * s(rng);
      Mat<2> domain;
      domain << 0.06 + 0.01 * s(rng), 0.01 * s(rng), 0.01 * s(rng), 0.06 + 0.01 * s(rng);
      Stencil<2> st;
      switch (kind) {
        case ShapeFunctionKind::linear:
          linear_stencil<2>(x, g, st);
          break;
        case ShapeFunctionKind::ugimp:
          ugimp_stencil<2>(x, 0.5 * domain.diagonal().cwiseAbs(), g, st);
          break;
        case ShapeFunctionKind::cpdi:
          cpdi_stencil<2>(x, domain, g, st);
          break;
        case ShapeFunctionKind::bspline2:
          bspline2_stencil<2>(x, g, st);
          break;
      }
      for (int e = 0; e < st.count; ++e) {
        node_mass[static_cast<std::size_t>(st.node[e])] += st.weight[e] * m;
        node_momentum[static_cast<std::size_t>(st.node[e])] += st.weight[e] * m * v;
      }
      mass += m;
      momentum += m * v;
    }
    double grid_mass = 0.0;
    Vec<2> grid_momentum = Vec<2>::Zero();
    for (std::size_t i = 0; i < node_mass.size(); ++i) {
      grid_mass += node_mass[i];
      grid_momentum += node_momentum[i];
    }
    EXPECT_NEAR(grid_mass / mass, 1.0, 1e-13) << static_cast<int>(kind);
    EXPECT_NEAR((grid_momentum - momentum).norm() / momentum.norm(), 0.0, 1e-12)
        << static_cast<int>(kind);
  }
}

TEST(ShapeFunctions, ReferenceCurvaturesAreTheHessiansSeenThroughF) {
  // bspline2_reference_curvatures against Fᵀ H F of bspline2_hessians, for sheared and stretched F.
  const auto g = test_grid();
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> u(0.0, 2.0), strain(-0.4, 0.4);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec<2> x(u(rng), u(rng));
    Mat<2> F;
    F << 1.0 + strain(rng), strain(rng), strain(rng), 1.0 + strain(rng);
    std::array<Mat<2>, Stencil<2>::capacity> hessian;
    bspline2_hessians<2>(x, g, hessian);
    std::array<Eigen::Vector3d, Stencil<2>::capacity> chi;
    bspline2_reference_curvatures(x, F, g, chi);
    for (int e = 0; e < 9; ++e) {
      const Mat<2> H = F.transpose() * hessian[e] * F;
      const double size = hessian[e].norm();
      EXPECT_NEAR(chi[e][0], H(0, 0), 1e-12 * size);
      EXPECT_NEAR(chi[e][1], H(1, 1), 1e-12 * size);
      EXPECT_NEAR(chi[e][2], H(0, 1), 1e-12 * size);
    }
  }
}

TEST(ShapeFunctions, BsplineStencilNodesAreTheEntriesWithWeight) {
  // bspline2_stencil_nodes lists the nodes of bspline2_stencil whose weight or gradient is not
  // zero, in entry order. At a cell's mid-point (x − x₀ = (k + ½) h) the third node of that
  // direction sits at the end knot, 1.5 h away, where weight and slope vanish: 6 of 9 entries
  // remain, and 4 at the mid-point of both directions.
  const auto g = test_grid();
  std::mt19937 rng(10);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  std::vector<Vec<2>> positions;
  for (int trial = 0; trial < 50; ++trial) positions.emplace_back(u(rng), u(rng));
  const Vec<2> mid_x(g.origin[0] + 3.5 * g.cell_size, g.origin[1] + 3.2 * g.cell_size);
  const Vec<2> mid_xy(g.origin[0] + 3.5 * g.cell_size, g.origin[1] + 2.5 * g.cell_size);
  positions.push_back(mid_x);
  positions.push_back(mid_xy);
  for (const Vec<2>& x : positions) {
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    std::vector<std::int64_t> expected;
    for (int e = 0; e < s.count; ++e)
      if (s.weight[e] != 0.0 || s.gradient[e].squaredNorm() != 0.0) expected.push_back(s.node[e]);
    std::array<std::int64_t, Stencil<2>::capacity> nodes;
    const int count = bspline2_stencil_nodes<2>(x, g, nodes);
    ASSERT_EQ(count, static_cast<int>(expected.size()));
    for (int k = 0; k < count; ++k) EXPECT_EQ(nodes[k], expected[static_cast<std::size_t>(k)]);
    if (x == mid_x) EXPECT_EQ(count, 6);
    if (x == mid_xy) EXPECT_EQ(count, 4);
  }
}

TEST(ShapeFunctions, QuadraticBsplineHessiansAreTheGradientsDerivatives) {
  // Central differences of the stencil's gradients, inside one knot span (the second derivatives
  // are constant there), against bspline2_hessians; and Σ ∂²S̄ = 0, Σ X ⊗ ∂²S̄ = 0 (a linear field
  // has no curvature).
  const auto g = test_grid();
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> u(0.0, 2.0);
  for (int trial = 0; trial < 100; ++trial) {
    Vec<2> x(u(rng), u(rng));
    // Keep x away from the knots (cell mid-points and nodes) by at least the difference step.
    for (int k = 0; k < 2; ++k) {
      const double t = (x[k] - g.origin[k]) * g.inverse_cell_size;
      const double f = t * 2.0 - std::floor(t * 2.0);
      if (f < 0.01 || f > 0.99) x[k] += 0.02 * g.cell_size;
    }
    Stencil<2> s;
    bspline2_stencil<2>(x, g, s);
    std::array<Mat<2>, Stencil<2>::capacity> hessian;
    bspline2_hessians<2>(x, g, hessian);
    Mat<2> sum = Mat<2>::Zero();
    for (int e = 0; e < s.count; ++e) sum += hessian[e];
    EXPECT_LT(sum.norm(), 1e-9);
    const double step = 1e-4 * g.cell_size;
    for (int k = 0; k < 2; ++k) {
      Vec<2> dx = Vec<2>::Zero();
      dx[k] = step;
      Stencil<2> plus, minus;
      bspline2_stencil<2>(x + dx, g, plus);
      bspline2_stencil<2>(x - dx, g, minus);
      for (int e = 0; e < s.count; ++e) {
        ASSERT_EQ(plus.node[e], s.node[e]);
        ASSERT_EQ(minus.node[e], s.node[e]);
        const Vec<2> column = (plus.gradient[e] - minus.gradient[e]) / (2.0 * step);
        EXPECT_NEAR((column - hessian[e].col(k)).norm(), 0.0, 1e-6 * 16.0 * 16.0);
      }
    }
  }
}
