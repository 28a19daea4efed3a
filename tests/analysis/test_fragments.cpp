// Fragments (docs/design.md): union-find labelling, fines, the raster cross-check, per-fragment
// shape statistics against closed forms, and the empirical CDFs.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <opencv2/core.hpp>
#include <random>
#include <vector>

#include "fragmpm/analysis/convex_hull_measures.hpp"
#include "fragmpm/analysis/distributions.hpp"
#include "fragmpm/analysis/fragment_raster.hpp"
#include "fragmpm/analysis/fragment_statistics.hpp"
#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/analysis/frame_fragments.hpp"
#include "fragmpm/analysis/frame_reference.hpp"
#include "fragmpm/analysis/union_find.hpp"

namespace fa = fragmpm::analysis;
namespace fm = fragmpm::mpm;
using std::numbers::pi;
using P2 = fm::Particles<2>;

namespace {

constexpr double kSpacing = 1e-4;    // 0.1 mm particles
constexpr double kDensity = 2650.0;  // kg/m³

/// Appends particles on a square lattice of spacing s (centres at (i + ½) s, (j + ½) s) whose
/// centres satisfy `inside`, undeformed, with square domains.
template <class Inside>
void add_lattice(P2& P, int nx, int ny, Inside inside, std::int32_t body = 0, double s = kSpacing) {
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const double x = (i + 0.5) * s, y = (j + 0.5) * s;
      if (!inside(x, y)) continue;
      const std::size_t p = P.size();
      P.resize(p + 1);
      P.x[p] = {x, y};
      P.volume0[p] = s * s;
      P.mass[p] = kDensity * s * s;
      P.domain[p] = fm::Mat<2>::Identity() * s;
      P.body[p] = body;
    }
}

/// Moves particles [first, last) rigidly by `shift`.
void translate(P2& P, std::size_t first, std::size_t last, const fm::Vec<2>& shift) {
  for (std::size_t p = first; p < last; ++p) P.x[p] += shift;
}

/// Rotates particles [first, last) rigidly by `angle` about `centre`: positions, domains and F.
void rotate(P2& P, std::size_t first, std::size_t last, double angle, const fm::Vec<2>& centre) {
  const fm::Mat<2> R = Eigen::Rotation2Dd(angle).toRotationMatrix();
  for (std::size_t p = first; p < last; ++p) {
    P.x[p] = centre + R * (P.x[p] - centre);
    P.domain[p] = R * P.domain[p];
    P.F[p] = R * P.F[p];
  }
}

fa::FragmentStatistics only_fragment(const P2& P) {
  const fa::FragmentLabels labels = fa::label_fragments(P, P);
  EXPECT_EQ(labels.count(), 1u);
  return fa::fragment_statistics(P, labels).at(0);
}

}  // namespace

TEST(UnionFind, JoinsSetsAndCountsTheirSizes) {
  fa::UnionFind u(6);
  EXPECT_TRUE(u.unite(0, 1));
  EXPECT_TRUE(u.unite(2, 3));
  EXPECT_TRUE(u.unite(1, 3));
  EXPECT_FALSE(u.unite(0, 2));
  EXPECT_EQ(u.find(0), u.find(3));
  EXPECT_NE(u.find(0), u.find(4));
  EXPECT_EQ(u.set_size(2), 4u);
  EXPECT_EQ(u.set_size(5), 1u);
}

TEST(FragmentShape, SquareOfParticlesHasExactAreaDiameterAndHull) {
  const int n = 24;
  P2 P;
  add_lattice(P, n, n, [](double, double) { return true; });
  for (std::size_t p = 0; p < P.size(); ++p) P.v[p] = {3.0 + P.x[p](1) * 1e3, -2.0};  // shear flow
  const fa::FragmentStatistics s = only_fragment(P);
  const double L = n * kSpacing;
  EXPECT_EQ(s.particles, n * n);
  EXPECT_NEAR(s.area / (L * L), 1.0, 1e-12);
  EXPECT_NEAR(s.equivalent_diameter / std::sqrt(4.0 * L * L / pi), 1.0, 1e-12);
  EXPECT_NEAR(s.roundness, 1.0, 1e-12);
  EXPECT_NEAR(s.aspect_ratio, 1.0, 1e-12);
  EXPECT_NEAR(s.solidity, 1.0, 1e-12);
  EXPECT_NEAR(s.convex_area / (L * L), 1.0, 1e-12);
  EXPECT_NEAR(s.feret_max / (std::numbers::sqrt2 * L), 1.0, 1e-12);
  EXPECT_NEAR(s.feret_min / L, 1.0, 1e-12);
  EXPECT_NEAR(s.centroid_x / (0.5 * L), 1.0, 1e-12);
  EXPECT_NEAR(s.centroid_y / (0.5 * L), 1.0, 1e-12);
  EXPECT_NEAR(s.mass / (kDensity * L * L), 1.0, 1e-12);
  EXPECT_NEAR(s.velocity_x, 3.0 + 0.5 * L * 1e3,
              1e-12);  // mean of a linear field = value at centroid
  EXPECT_NEAR(s.velocity_y, -2.0, 1e-12);
  EXPECT_TRUE(std::isnan(s.temperature));
  // Four-direction Crofton on an axis-aligned square: π/8 (4L + 8L/√2) ≈ 0.948 · 4L (its known
  // bias for this worst-case orientation; unbiased on average over orientations), less a little
  // for the corners rounded by the outline smoothing.
  const double crofton = pi / 8.0 * (4.0 + 8.0 / std::numbers::sqrt2) * L;
  EXPECT_NEAR(s.perimeter / crofton, 1.0, 0.02);
}

TEST(FragmentShape, DiskOfParticlesIsRound) {
  const double R = 20.5 * kSpacing;
  P2 P;
  add_lattice(P, 41, 41, [&](double x, double y) { return std::hypot(x - R, y - R) < R; });
  const fa::FragmentStatistics s = only_fragment(P);
  EXPECT_GT(s.roundness, 0.97);
  EXPECT_NEAR(s.equivalent_diameter / (2.0 * R), 1.0, 0.01);
  EXPECT_NEAR(s.perimeter / (2.0 * pi * R), 1.0, 0.03);
  EXPECT_NEAR(s.feret_max / (2.0 * R), 1.0, 0.03);
  EXPECT_NEAR(s.feret_min / (2.0 * R), 1.0, 0.03);
  EXPECT_GT(s.solidity, 0.97);
  EXPECT_LE(s.solidity, 1.0);
}

TEST(FragmentShape, TwoToOneEllipseHasRoundnessOneHalf) {
  const double a = 40.0 * kSpacing, b = 20.0 * kSpacing;
  P2 P;
  add_lattice(P, 82, 42, [&](double x, double y) {
    const double u = (x - 41 * kSpacing) / a, v = (y - 21 * kSpacing) / b;
    return u * u + v * v < 1.0;
  });
  const std::size_t n = P.size();
  rotate(P, 0, n, pi / 6, {41 * kSpacing, 21 * kSpacing});  // orientation must not matter
  const fa::FragmentStatistics s = only_fragment(P);
  EXPECT_NEAR(s.roundness, 0.50, 0.02);
  EXPECT_NEAR(s.aspect_ratio, 2.0, 0.08);
  EXPECT_NEAR(s.orientation, pi / 6, 0.01);
  EXPECT_NEAR(s.equivalent_diameter / (2.0 * std::sqrt(a * b)), 1.0, 0.01);
  EXPECT_NEAR(s.feret_max / (2.0 * a), 1.0, 0.03);
  EXPECT_NEAR(s.feret_min / (2.0 * b), 1.0, 0.05);
}

TEST(FragmentShape, HomogeneousDeformationScalesTheArea) {
  P2 P;
  add_lattice(P, 10, 10, [](double, double) { return true; });
  fm::Mat<2> F;
  F << 1.2, 0.3, 0.0, 0.9;  // stretch and shear, det 1.08
  for (std::size_t p = 0; p < P.size(); ++p) {
    P.x[p] = F * P.x[p];
    P.domain[p] = F * P.domain[p];
    P.F[p] = F;
  }
  P2 reference;
  add_lattice(reference, 10, 10, [](double, double) { return true; });
  const fa::FragmentLabels labels = fa::label_fragments(reference, P);
  ASSERT_EQ(labels.count(), 1u);
  const fa::FragmentStatistics s = fa::fragment_statistics(P, labels).at(0);
  const double A = 1.08 * std::pow(10 * kSpacing, 2);
  EXPECT_NEAR(s.area / A, 1.0, 1e-12);
  EXPECT_NEAR(s.convex_area / A, 1.0, 1e-12);  // a parallelogram is its own hull
  EXPECT_NEAR(s.solidity, 1.0, 1e-12);
}

TEST(FragmentLabels, MaskedRowSplitsABodyInTwo) {
  P2 P;
  add_lattice(P, 20, 21, [](double, double) { return true; });
  for (std::size_t p = 0; p < P.size(); ++p)
    if (std::abs(P.x[p](1) - 10.5 * kSpacing) < 0.1 * kSpacing) P.damage[p] = 1.0;
  fa::FragmentLabels labels = fa::label_fragments(P, P);
  EXPECT_EQ(labels.count(), 2u);
  EXPECT_EQ(labels.masked, 20u);
  EXPECT_EQ(labels.particles[0], 200);
  EXPECT_EQ(labels.particles[1], 200);
  EXPECT_EQ(labels.fines(), 0u);
  // Below the mask threshold the row still holds the body together.
  for (double& d : P.damage)
    if (d == 1.0) d = 0.98;
  labels = fa::label_fragments(P, P);
  EXPECT_EQ(labels.count(), 1u);
  EXPECT_EQ(labels.masked, 0u);
  // A lower threshold masks it again.
  fa::FragmentOptions o;
  o.d_mask = 0.95;
  EXPECT_EQ(fa::label_fragments(P, P, o).count(), 2u);
}

TEST(FragmentLabels, FragmentsPressedTogetherStayTwo) {
  // Reference: two 10 x 10 blocks three spacings apart. Current: the right block pushed against the
  // left one (their domains touch), as fragments squeezed between platens are.
  P2 ref;
  add_lattice(ref, 23, 10, [](double x, double) { return x < 10 * kSpacing || x > 13 * kSpacing; });
  P2 now = ref;
  std::size_t first_right = 0;
  while (ref.x[first_right](0) < 10 * kSpacing) ++first_right;
  for (std::size_t p = 0; p < now.size(); ++p)
    if (now.x[p](0) > 13 * kSpacing) now.x[p](0) -= 3 * kSpacing;
  const fa::FragmentLabels labels = fa::label_fragments(ref, now);
  EXPECT_EQ(labels.count(), 2u);
  EXPECT_EQ(labels.particles[0], 100);
  EXPECT_EQ(labels.particles[1], 100);
  // The picture cannot tell them apart: one component, which the comparison reports as merged.
  const fa::LabellingComparison c =
      fa::compare_labellings(labels, fa::raster_fragments(now, labels));
  EXPECT_EQ(c.raster_components, 1u);
  EXPECT_EQ(c.merged, 1u);
  EXPECT_FALSE(c.agree());
  (void)first_right;
}

TEST(FragmentLabels, GrainsTouchingInTheReferenceAreSeparateBodies) {
  P2 P;
  add_lattice(
      P, 10, 10, [](double x, double) { return x < 5 * kSpacing; }, 0);
  add_lattice(
      P, 10, 10, [](double x, double) { return x > 5 * kSpacing; }, 1);
  EXPECT_EQ(fa::label_fragments(P, P).count(), 2u);
}

TEST(FragmentLabels, OpeningCrackSeparatesWithoutMask) {
  P2 ref;
  add_lattice(ref, 12, 12, [](double, double) { return true; });
  P2 now = ref;
  for (std::size_t p = 0; p < now.size(); ++p)
    if (now.x[p](1) > 6 * kSpacing) now.x[p](1) += 0.6 * kSpacing;  // 1.6 spacings apart > 1.5
  EXPECT_EQ(fa::label_fragments(ref, now).count(), 2u);
  for (std::size_t p = 0; p < now.size(); ++p)
    if (now.x[p](1) > 6 * kSpacing) now.x[p](1) -= 0.2 * kSpacing;  // 1.4 spacings: still bonded
  EXPECT_EQ(fa::label_fragments(ref, now).count(), 1u);
}

TEST(FragmentLabels, FinesBelowTheMinimumParticleCount) {
  P2 P;
  add_lattice(P, 10, 10, [](double, double) { return true; });  // 100
  auto add_single = [&](double x, double y) {
    add_lattice(P, 1, 1, [](double, double) { return true; });
    P.x.back() = {x, y};
  };
  add_single(20 * kSpacing, 0.5 * kSpacing);
  add_single(25 * kSpacing, 0.5 * kSpacing);
  add_single(30 * kSpacing, 0.5 * kSpacing);
  add_single(35 * kSpacing, 0.5 * kSpacing);  // a pair …
  add_single(36 * kSpacing, 0.5 * kSpacing);
  for (int k = 0; k < 4; ++k) add_single((40 + k) * kSpacing, 0.5 * kSpacing);  // … and a row of 4

  fa::FragmentLabels labels = fa::label_fragments(P, P);  // default minimum: 4 particles
  ASSERT_EQ(labels.count(), 6u);
  EXPECT_EQ(labels.fines(), 4u);  // 3 singles and the pair
  EXPECT_EQ(labels.resolved(), 2u);
  EXPECT_EQ(labels.particles[0], 100);
  EXPECT_EQ(labels.particles[1], 4);
  EXPECT_EQ(labels.particles[2], 2);
  EXPECT_FALSE(labels.fine[1]);
  EXPECT_TRUE(labels.fine[2]);

  fa::FragmentOptions o;
  o.min_particles = 2;
  labels = fa::label_fragments(P, P, o);
  EXPECT_EQ(labels.fines(), 3u);

  const fa::FrameFragments frame = fa::analyze_fragments(P, P, {});
  EXPECT_EQ(frame.fragments.size(), 2u);
  EXPECT_EQ(frame.fines.size(), 4u);
  EXPECT_EQ(frame.summary.fines, 4u);
  EXPECT_EQ(frame.summary.fine_particles, 5);
  EXPECT_NEAR(frame.summary.fines_mass / (5 * kDensity * kSpacing * kSpacing), 1.0, 1e-12);
  EXPECT_EQ(frame.equivalent_diameter.value.size(), 2u);  // the CDFs cover resolved fragments
}

TEST(FragmentRaster, AgreesWithTheGraphOnSeparatedFragments) {
  P2 P;
  const double s = kSpacing;
  // A disk, a rotated ellipse, a body split by a masked row, and a rotated square, all well apart.
  add_lattice(
      P, 20, 20, [&](double x, double y) { return std::hypot(x - 10 * s, y - 10 * s) < 9.5 * s; },
      0);
  std::size_t mark = P.size();
  add_lattice(
      P, 30, 16,
      [&](double x, double y) {
        const double u = (x - 15 * s) / (14 * s), v = (y - 8 * s) / (7 * s);
        return u * u + v * v < 1.0;
      },
      1);
  rotate(P, mark, P.size(), 0.4, {15 * s, 8 * s});
  translate(P, mark, P.size(), {30 * s, 0.0});
  mark = P.size();
  add_lattice(
      P, 12, 15, [](double, double) { return true; }, 2);
  for (std::size_t p = mark; p < P.size(); ++p)
    if (std::abs(P.x[p](1) - 7.5 * s) < 0.1 * s) P.damage[p] = 1.0;
  translate(P, mark, P.size(), {0.0, 30 * s});
  mark = P.size();
  add_lattice(
      P, 8, 8, [](double, double) { return true; }, 3);
  rotate(P, mark, P.size(), 0.7, {4 * s, 4 * s});
  translate(P, mark, P.size(), {30 * s, 30 * s});

  const fa::FragmentLabels labels = fa::label_fragments(P, P);
  EXPECT_EQ(labels.count(), 5u);
  const fa::RasterLabels raster = fa::raster_fragments(P, labels);
  const fa::LabellingComparison c = fa::compare_labellings(labels, raster);
  EXPECT_TRUE(c.agree()) << c.summary();
  EXPECT_EQ(c.raster_components, 5u);
  // Also at a coarser raster, one pixel per half spacing.
  EXPECT_TRUE(fa::compare_labellings(labels, fa::raster_fragments(P, labels, 0.5 * s)).agree());
}

TEST(FragmentRaster, DomainsTileWithoutGapsOrOverlap) {
  // 7 x 5 particles with pixel size s/4: the mask is exactly 28 x 20 pixels.
  P2 P;
  add_lattice(P, 7, 5, [](double, double) { return true; });
  std::vector<std::size_t> all(P.size());
  for (std::size_t p = 0; p < all.size(); ++p) all[p] = p;
  const fa::ParticleRaster r = fa::draw_particle_domains(P, all, 0.25 * kSpacing, 2);
  EXPECT_EQ(cv::countNonZero(r.mask), 28 * 20);
  EXPECT_THROW(fa::draw_particle_domains(P, all, 0.0), std::invalid_argument);
}

TEST(ConvexHullMeasures, MatchBruteForceOnRandomPoints) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<Eigen::Vector2d> pts;
    for (int k = 0; k < 60; ++k) pts.emplace_back(u(rng), 0.4 * u(rng));
    const fa::ConvexMeasures m = fa::convex_hull_measures(pts);
    double diameter = 0.0;
    for (const auto& a : pts)
      for (const auto& b : pts) diameter = std::max(diameter, (a - b).norm());
    EXPECT_NEAR(m.feret_max, diameter, 1e-12);
    // Minimum width: the smallest extent of the points over many directions bounds it from above.
    double width = INFINITY;
    for (int k = 0; k < 20000; ++k) {
      const double t = pi * k / 20000;
      const Eigen::Vector2d n(std::cos(t), std::sin(t));
      double lo = INFINITY, hi = -INFINITY;
      for (const auto& a : pts) {
        lo = std::min(lo, a.dot(n));
        hi = std::max(hi, a.dot(n));
      }
      width = std::min(width, hi - lo);
    }
    EXPECT_LE(m.feret_min, width + 1e-12);
    EXPECT_NEAR(m.feret_min, width, 1e-4);
  }
  const std::vector<Eigen::Vector2d> rect{{0, 0}, {3, 0}, {3, 1}, {0, 1}, {1.5, 0.5}};
  const fa::ConvexMeasures r = fa::convex_hull_measures(rect);
  EXPECT_EQ(r.hull_vertices, 4u);
  EXPECT_NEAR(r.hull_area, 3.0, 1e-15);
  EXPECT_NEAR(r.hull_perimeter, 8.0, 1e-15);
  EXPECT_NEAR(r.feret_max, std::sqrt(10.0), 1e-15);
  EXPECT_NEAR(r.feret_min, 1.0, 1e-15);
}

TEST(Distributions, CdfIsMonotoneAndEndsAtOne) {
  const std::vector<double> values{3.0, 1.0, 2.0, 2.0};
  const std::vector<double> mass{1.0, 1.0, 2.0, 4.0};
  const fa::EmpiricalCdf c = fa::empirical_cdf(values, mass);
  EXPECT_EQ(c.value, (std::vector<double>{1.0, 2.0, 2.0, 3.0}));
  EXPECT_EQ(c.number_fraction, (std::vector<double>{0.25, 0.5, 0.75, 1.0}));
  EXPECT_EQ(c.mass_fraction, (std::vector<double>{0.125, 0.375, 0.875, 1.0}));
  EXPECT_THROW(fa::empirical_cdf(values, std::vector<double>{1, 1, 1}), std::invalid_argument);
  EXPECT_THROW(fa::empirical_cdf(values, std::vector<double>{0, 0, 0, 0}), std::invalid_argument);
  EXPECT_THROW(fa::empirical_cdf(values, std::vector<double>{1, -1, 1, 1}), std::invalid_argument);
}

TEST(Distributions, FragmentCdfsOfACrushedBlockAreMonotoneAndEndAtOne) {
  // A block cut into pieces of different sizes by masked rows and columns.
  P2 P;
  add_lattice(P, 40, 40, [](double, double) { return true; });
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cut(1, 38);
  std::vector<int> rows, cols;
  for (int k = 0; k < 5; ++k) rows.push_back(cut(rng)), cols.push_back(cut(rng));
  for (std::size_t p = 0; p < P.size(); ++p) {
    const int i = static_cast<int>(P.x[p](0) / kSpacing),
              j = static_cast<int>(P.x[p](1) / kSpacing);
    for (const int r : rows) P.damage[p] = (j == r) ? 1.0 : P.damage[p];
    for (const int c : cols) P.damage[p] = (i == c) ? 1.0 : P.damage[p];
  }
  const fa::FrameFragments f = fa::analyze_fragments(P, P, {});
  ASSERT_GT(f.fragments.size(), 5u);
  EXPECT_TRUE(f.raster_checked);
  EXPECT_TRUE(f.raster.agree()) << f.raster.summary();
  for (const fa::EmpiricalCdf* c : {&f.equivalent_diameter, &f.roundness}) {
    ASSERT_EQ(c->value.size(), f.fragments.size());
    for (std::size_t k = 1; k < c->value.size(); ++k) {
      EXPECT_GE(c->value[k], c->value[k - 1]);
      EXPECT_GE(c->number_fraction[k], c->number_fraction[k - 1]);
      EXPECT_GE(c->mass_fraction[k], c->mass_fraction[k - 1]);
    }
    EXPECT_EQ(c->number_fraction.back(), 1.0);
    EXPECT_EQ(c->mass_fraction.back(), 1.0);
  }
  // Rectangles of whole particles: every fragment's area is an integer number of particle areas.
  double total = 0.0;
  for (const auto& s : f.fragments) {
    EXPECT_NEAR(s.area / (s.particles * kSpacing * kSpacing), 1.0, 1e-12);
    total += s.mass;
  }
  EXPECT_NEAR(total, f.summary.fragment_mass, 1e-12 * total);
}

TEST(FragmentLabels, RejectsBadInput) {
  P2 a, b;
  add_lattice(a, 3, 3, [](double, double) { return true; });
  add_lattice(b, 2, 3, [](double, double) { return true; });
  EXPECT_THROW(fa::label_fragments(a, b), std::invalid_argument);
  fa::FragmentOptions o;
  o.d_mask = 1.5;
  EXPECT_THROW(fa::label_fragments(a, a, o), std::invalid_argument);
  o = {};
  o.min_particles = 0;
  EXPECT_THROW(fa::label_fragments(a, a, o), std::invalid_argument);
}

TEST(FragmentLabels, LargeBlockIsOneFragment) {
  P2 P;
  add_lattice(P, 300, 300, [](double, double) { return true; });  // 90 000 particles, bin search
  const fa::FragmentLabels labels = fa::label_fragments(P, P);
  EXPECT_EQ(labels.count(), 1u);
  EXPECT_EQ(labels.particles[0], 90000);
}

TEST(FrameReference, MatchesTheRemainingParticlesByIdAndCountsTheDeparted) {
  fm::Particles<2> first;
  first.resize(5);
  for (std::size_t p = 0; p < 5; ++p) {
    first.x[p] = fm::Vec<2>(double(p), 0.0);
    first.mass[p] = 1.0 + double(p);  // 1 … 5
  }
  // Particles 0 and 3 left the domain; the others moved by (0, 1).
  fm::Particles<2> current = first.select({1, 2, 4});
  for (auto& x : current.x) x[1] += 1.0;
  const fa::FrameReference r = fa::frame_reference(first, current);
  EXPECT_EQ(r.departed, 2u);
  EXPECT_EQ(r.departed_mass, 1.0 + 4.0);
  ASSERT_EQ(r.particles.size(), 3u);
  EXPECT_EQ(r.particles.id, (std::vector<std::int32_t>{1, 2, 4}));
  EXPECT_EQ(r.particles.x[2], fm::Vec<2>(4.0, 0.0));  // the reference position, not the current

  fm::Particles<2> twice = first.select({1, 1});
  EXPECT_THROW(fa::frame_reference(first, twice), std::invalid_argument);
  fm::Particles<2> stranger = first.select({2});
  stranger.id[0] = 7;
  EXPECT_THROW(fa::frame_reference(first, stranger), std::invalid_argument);
}
