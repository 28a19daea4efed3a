// Shape-function invariants: partition of unity, zero-sum gradients (a constant field has zero
// gradient), exact gradient of a linear field, and CPDI = linear for an undeformed particle inside
// one cell (the bilinear hat averaged over a centred box equals its centre value, [XLS21] eq.
// (52)-(53)).
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
