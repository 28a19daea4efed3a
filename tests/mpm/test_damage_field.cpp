// Kernel damage field and DFG partitioning rules ([HH17] eq. (17)-(19), Alg. 1-2; [XLS21] eq.
// (67)-(69)), and the Verlet neighbour lists they run on.
//
// Exact answers used: on a square (cubic) lattice the neighbourhood of an interior particle is
// symmetric under inversion and 90° rotations, so Σ ω r = 0 and Σ (1 − r̄) r ⊗ r ∝ I; for a linear
// d̂ = a + b·x this gives D̄(x_p) = d̂_p and ∇D̄ ∥ b exactly. For constant d̂ = c the normalised field
// is c and its gradient zero at every particle, edges included. A straight band of d̂ = 1 particles
// gives particle gradients that point into the band from both sides.
#include <gtest/gtest.h>
#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <set>

#include "fragmpm/mpm/damage_field.hpp"
#include "fragmpm/mpm/shape_functions.hpp"

using namespace fragmpm::mpm;

namespace {

/// Particles at origin + (i + 1/2) s on an n[0] × … lattice.
template <int D>
std::vector<Vec<D>> lattice(const IVec<D>& n, double s, const Vec<D>& origin = Vec<D>::Zero()) {
  std::vector<Vec<D>> x;
  std::int64_t total = 1;
  for (int k = 0; k < D; ++k) total *= n[k];
  for (std::int64_t i = 0; i < total; ++i) {
    Vec<D> p;
    std::int64_t rest = i;
    for (int k = 0; k < D; ++k) {
      p[k] = origin[k] + (static_cast<double>(rest % n[k]) + 0.5) * s;
      rest /= n[k];
    }
    x.push_back(p);
  }
  return x;
}

template <int D>
std::vector<Vec<D>> random_points(std::size_t n, double box, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(0.0, box);
  std::vector<Vec<D>> x(n);
  for (auto& p : x)
    for (int k = 0; k < D; ++k) p[k] = u(rng);
  return x;
}

template <int D>
std::set<std::uint32_t> listed(const NeighbourLists<D>& lists, std::size_t p) {
  const auto row = lists.neighbours(p);
  return {row.begin(), row.end()};
}

/// Every pair with |x_p − x_q| < radius is listed (both ways); returns how many such pairs.
template <int D>
std::size_t expect_no_missed_pair(const NeighbourLists<D>& lists, const std::vector<Vec<D>>& x,
                                  double radius) {
  std::size_t pairs = 0, missed = 0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    const auto row = listed(lists, p);
    for (std::size_t q = 0; q < x.size(); ++q) {
      if (q == p || (x[p] - x[q]).norm() >= radius) continue;
      ++pairs;
      if (!row.count(static_cast<std::uint32_t>(q))) ++missed;
    }
  }
  EXPECT_EQ(missed, 0u);
  return pairs;
}

/// After a build the lists are exactly the pairs within r_list.
template <int D>
void expect_exact_lists(const NeighbourLists<D>& lists, const std::vector<Vec<D>>& x) {
  const double r2 = lists.list_radius() * lists.list_radius();
  for (std::size_t p = 0; p < x.size(); ++p) {
    std::set<std::uint32_t> brute;
    for (std::size_t q = 0; q < x.size(); ++q)
      if (q != p && (x[p] - x[q]).squaredNorm() <= r2) brute.insert(static_cast<std::uint32_t>(q));
    const auto row = lists.neighbours(p);
    ASSERT_EQ(row.size(), brute.size()) << "particle " << p;  // no duplicates either
    EXPECT_EQ(listed(lists, p), brute) << "particle " << p;
  }
}

template <int D>
double angle_between_lines_deg(const Vec<D>& a, const Vec<D>& b) {
  const double c = std::min(1.0, std::abs(a.dot(b)) / (a.norm() * b.norm()));
  return std::acos(c) * 180.0 / std::numbers::pi;
}

template <int D>
void run_field(const std::vector<Vec<D>>& x, const std::vector<double>& dhat, double radius,
               std::vector<double>& field, std::vector<Vec<D>>& gradient) {
  NeighbourLists<D> lists;
  lists.update(x, radius, 0.2);
  damage_field_gradient<D>(lists, x, dhat, radius, field, gradient);
}

}  // namespace

// ---- Neighbour lists ----

TEST(NeighbourLists, BuildEqualsBruteForce2DAnd3D) {
  std::mt19937 rng(7);
  {
    const auto x = random_points<2>(1500, 1.0, rng);
    NeighbourLists<2> lists;
    EXPECT_TRUE(lists.update(x, 0.05, 0.25));
    EXPECT_DOUBLE_EQ(lists.list_radius(), 0.0625);
    expect_exact_lists(lists, x);
    EXPECT_GT(expect_no_missed_pair(lists, x, 0.05), 1000u);
  }
  {
    const auto x = random_points<3>(1500, 1.0, rng);
    NeighbourLists<3> lists;
    EXPECT_TRUE(lists.update(x, 0.12, 0.1));
    expect_exact_lists(lists, x);
    EXPECT_GT(expect_no_missed_pair(lists, x, 0.12), 1000u);
  }
}

// Random moves, some steps below and some above the skin: update() rebuilds exactly when the two
// largest displacements since the last build exceed the skin, and no pair within r_p is ever
// missed.
TEST(NeighbourLists, RandomMovesRebuildExactlyWhenNeededAndMissNoPair) {
  std::mt19937 rng(11);
  const double radius = 0.06, fraction = 0.3, skin = fraction * radius;
  auto x = random_points<2>(800, 1.0, rng);
  NeighbourLists<2> lists;
  ASSERT_TRUE(lists.update(x, radius, fraction));
  auto reference = x;
  int rebuilds = 0, kept = 0;
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  for (int step = 0; step < 45; ++step) {
    // Alternate gentle drifts (many steps per rebuild) with occasional jumps of a single particle.
    const double amplitude = (step % 7 == 3) ? 0.0 : 0.02 * skin * (1 + step % 4);
    for (auto& p : x) p += amplitude * Vec<2>(unit(rng), unit(rng));
    if (step % 7 == 3) x[static_cast<std::size_t>(step) % x.size()] += Vec<2>(0.7 * skin, 0.0);
    std::vector<double> u;
    for (std::size_t p = 0; p < x.size(); ++p) u.push_back((x[p] - reference[p]).norm());
    std::partial_sort(u.begin(), u.begin() + 2, u.end(), std::greater<>());
    const bool expected = u[0] + u[1] > skin;
    const std::size_t builds_before = lists.builds();
    EXPECT_EQ(lists.update(x, radius, fraction), expected) << "step " << step;
    EXPECT_EQ(lists.builds(), builds_before + (expected ? 1 : 0));
    if (expected) {
      reference = x;
      ++rebuilds;
      expect_exact_lists(lists, x);
    } else {
      ++kept;
    }
    expect_no_missed_pair(lists, x, radius);
  }
  EXPECT_GT(rebuilds, 3);  // the sequence exercises both branches
  EXPECT_GT(kept, 15);
}

// The criterion is sharp: a pair just outside r_list that closes by the skin minus ε is still
// farther than r_p (no rebuild needed, none done); closing by the skin plus ε brings it inside r_p
// and triggers the rebuild that lists it. One particle alone may move up to the whole skin.
TEST(NeighbourLists, SkinCriterionIsSharp) {
  const double radius = 1.0, fraction = 0.2, skin = 0.2, eps = 1e-9;
  const double gap = radius + skin + eps;  // not listed at build
  std::vector<Vec<2>> x = {Vec<2>(0, 0), Vec<2>(gap, 0), Vec<2>(10, 10)};
  NeighbourLists<2> lists;
  ASSERT_TRUE(lists.update(x, radius, fraction));
  EXPECT_TRUE(lists.neighbours(0).empty());

  x[0].x() += 0.5 * skin - eps;  // each moves just under half the skin towards the other
  x[1].x() -= 0.5 * skin - eps;
  EXPECT_FALSE(lists.update(x, radius, fraction));
  EXPECT_GT((x[1] - x[0]).norm(), radius);
  EXPECT_TRUE(lists.neighbours(0).empty());

  x[0].x() += 2 * eps;  // now u(1) + u(2) = skin + ε and the pair is inside r_p
  x[1].x() -= 2 * eps;
  EXPECT_LT((x[1] - x[0]).norm(), radius);
  EXPECT_TRUE(lists.update(x, radius, fraction));
  ASSERT_EQ(lists.neighbours(0).size(), 1u);
  EXPECT_EQ(lists.neighbours(0)[0], 1u);
  EXPECT_EQ(lists.builds(), 2u);

  // One fast particle: u(1) = 0.9 skin, u(2) = 0 → no rebuild (the "f r_p / 2" rule would rebuild).
  x[2].y() += 0.9 * skin;
  EXPECT_FALSE(lists.update(x, radius, fraction));
  // Changing the radius or the particle count always rebuilds.
  EXPECT_TRUE(lists.update(x, 1.1 * radius, fraction));
  x.push_back(Vec<2>(5, 5));
  EXPECT_TRUE(lists.update(x, 1.1 * radius, fraction));
  EXPECT_EQ(lists.builds(), 4u);
}

TEST(NeighbourLists, BadInputThrows) {
  NeighbourLists<2> lists;
  std::vector<Vec<2>> x = {Vec<2>(0, 0), Vec<2>(1, 0)};
  EXPECT_THROW(lists.update(x, 0.0, 0.2), std::invalid_argument);
  EXPECT_THROW(lists.update(x, 1.0, -0.1), std::invalid_argument);
  x[1].y() = std::nan("");
  EXPECT_THROW(lists.update(x, 1.0, 0.2), std::invalid_argument);
  x[1].y() = 0.0;
  ASSERT_TRUE(lists.update(x, 1.0, 0.2));
  x[1].y() =
      std::numeric_limits<double>::infinity();  // a NaN/inf move forces a rebuild, which names it
  EXPECT_THROW(lists.update(x, 1.0, 0.2), std::invalid_argument);
  x[1].y() = 0.0;  // the failed rebuild left the lists as they were
  EXPECT_FALSE(lists.update(x, 1.0, 0.2));
  EXPECT_EQ(lists.builds(), 1u);
  ASSERT_EQ(lists.neighbours(0).size(), 1u);
}

// Particles spread over a box far larger than their count would fill: the bin edge grows, the lists
// stay exact.
TEST(NeighbourLists, SparseFarFlungParticlesStayExact) {
  std::mt19937 rng(5);
  auto x = random_points<2>(400, 1.0, rng);
  for (std::size_t p = 0; p < 40; ++p) x[p] += Vec<2>(5000.0 + p, -3000.0);
  NeighbourLists<2> lists;
  lists.update(x, 0.03, 0.2);
  EXPECT_LE(lists.bin_count(), 4096u);
  expect_exact_lists(lists, x);
}

// mark_near_nonzero may over-mark (bins are coarser than r_list) but never misses a particle
// that has a non-zero value among itself and its listed neighbours.
TEST(NeighbourLists, MarkNearNonzeroCoversEveryListedNeighbour) {
  std::mt19937 rng(13);
  for (const double fraction : {0.0, 0.25}) {
    const auto x = random_points<3>(3000, 1.0, rng);
    NeighbourLists<3> lists;
    lists.update(x, 0.08, fraction);
    std::vector<double> value(x.size(), 0.0);
    EXPECT_FALSE(lists.mark_near_nonzero(value));
    for (std::size_t p = 0; p < x.size(); p += 97) value[p] = 0.5;
    ASSERT_TRUE(lists.mark_near_nonzero(value));
    std::size_t marked = 0;
    for (std::size_t p = 0; p < x.size(); ++p) {
      bool needed = value[p] != 0.0;
      for (const std::uint32_t q : lists.neighbours(p)) needed = needed || value[q] != 0.0;
      if (needed) {
        EXPECT_TRUE(lists.near_marked(p)) << "particle " << p;
      }
      marked += lists.near_marked(p);
    }
    EXPECT_LT(marked, x.size());  // and it does skip something
  }
}

// ---- Kernel damage field ----

TEST(DamageField, KernelValues) {
  EXPECT_DOUBLE_EQ(damage_kernel(0.0), 1.0);
  EXPECT_DOUBLE_EQ(damage_kernel(0.5), 0.5);  // 1 − 3/4 + 1/4
  EXPECT_DOUBLE_EQ(damage_kernel(1.0), 0.0);
  EXPECT_DOUBLE_EQ(damage_kernel(1.5), 0.0);
}

// Gradient against central finite differences of the normalised field at a particle: move the
// particle and recompute D̄ at its new position with the same neighbours.
TEST(DamageField, GradientMatchesFiniteDifferences) {
  std::mt19937 rng(3);
  auto x = random_points<2>(600, 1.0, rng);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> dhat(x.size());
  for (auto& d : dhat) d = u(rng);
  const double radius = 0.09;
  std::vector<double> field;
  std::vector<Vec<2>> gradient;
  run_field(x, dhat, radius, field, gradient);
  const double step = 1e-6;
  for (std::size_t p = 0; p < 50; ++p) {
    Vec<2> fd;
    for (int k = 0; k < 2; ++k) {
      double value[2];
      for (int side = 0; side < 2; ++side) {
        Vec<2> xp = x[p];
        xp[k] += side ? step : -step;
        double sw = 0, sdw = 0;
        for (std::size_t q = 0; q < x.size(); ++q) {
          const double w = damage_kernel((q == p ? 0.0 : (xp - x[q]).norm()) / radius);
          sw += w;
          sdw += dhat[q] * w;
        }
        value[side] = sdw / sw;
      }
      fd[k] = (value[1] - value[0]) / (2 * step);
    }
    EXPECT_NEAR((gradient[p] - fd).norm(), 0.0, 1e-6 * (1.0 + fd.norm())) << "particle " << p;
  }
}

// d̂ linear in x: in the interior (neighbourhood complete) D̄(x_p) = d̂_p and ∇D̄ is parallel to the
// ramp direction, to round-off, in 2D for several directions and in 3D.
TEST(DamageField, LinearRampGivesExactDirectionInTheInterior) {
  const double h = 1e-3, s = h / 2, radius = std::sqrt(2.0) * h;
  const auto x = lattice<2>(IVec<2>(40, 40), s);
  for (const double degrees : {0.0, 30.0, 45.0, 73.0}) {
    const double a = degrees * std::numbers::pi / 180.0;
    const Vec<2> n(std::cos(a), std::sin(a));
    std::vector<double> dhat;
    for (const auto& p : x) dhat.push_back(0.3 + 0.015 / h * n.dot(p - Vec<2>(10 * h, 10 * h)));
    std::vector<double> field;
    std::vector<Vec<2>> gradient;
    run_field(x, dhat, radius, field, gradient);
    int interior = 0;
    for (std::size_t p = 0; p < x.size(); ++p) {
      const double margin = std::min({x[p].x(), x[p].y(), 20 * h - x[p].x(), 20 * h - x[p].y()});
      if (margin <= radius) continue;
      ++interior;
      EXPECT_NEAR(field[p], dhat[p], 1e-13);
      const double cross = gradient[p].x() * n.y() - gradient[p].y() * n.x();
      EXPECT_NEAR(cross / gradient[p].norm(), 0.0, 1e-12) << degrees << "° particle " << p;
      EXPECT_GT(gradient[p].dot(n), 0.0);
    }
    EXPECT_GT(interior, 900);
  }
  // 3D: cubic lattice, ramp along (1, 2, 2)/3.
  const auto x3 = lattice<3>(IVec<3>(14, 14, 14), s);
  const double radius3 = std::sqrt(3.0) * h;
  const Vec<3> n3 = Vec<3>(1, 2, 2) / 3.0;
  std::vector<double> dhat3;
  for (const auto& p : x3) dhat3.push_back(0.5 + 0.02 / h * n3.dot(p - Vec<3>::Constant(3.5 * h)));
  std::vector<double> field3;
  std::vector<Vec<3>> gradient3;
  run_field(x3, dhat3, radius3, field3, gradient3);
  int interior3 = 0;
  for (std::size_t p = 0; p < x3.size(); ++p) {
    const double margin = std::min(x3[p].minCoeff(), 7 * h - x3[p].maxCoeff());
    if (margin <= radius3) continue;
    ++interior3;
    EXPECT_NEAR(field3[p], dhat3[p], 1e-13);
    EXPECT_NEAR(gradient3[p].cross(n3).norm() / gradient3[p].norm(), 0.0, 1e-12);
    EXPECT_GT(gradient3[p].dot(n3), 0.0);
  }
  EXPECT_GT(interior3, 60);
}

// Constant d̂ = c: the normalised field is c and the gradient zero at every particle, also at free
// edges and corners and for irregular spacing ([HH17] Fig. 4c); the unnormalised sum would not be.
TEST(DamageField, NormalisationRemovesEdgeEffects) {
  const double h = 1e-3, radius = std::sqrt(2.0) * h, c = 0.37;
  std::mt19937 rng(9);
  std::uniform_real_distribution<double> jitter(-0.1 * h, 0.1 * h);
  auto x = lattice<2>(IVec<2>(30, 20), h / 2);
  for (auto& p : x) p += Vec<2>(jitter(rng), jitter(rng));
  std::vector<double> field;
  std::vector<Vec<2>> gradient;
  run_field(x, std::vector<double>(x.size(), c), radius, field, gradient);
  for (std::size_t p = 0; p < x.size(); ++p) {
    EXPECT_NEAR(field[p], c, 1e-15);
    EXPECT_LT(gradient[p].norm() * radius, 1e-13) << "particle " << p;
  }
  auto x3 = lattice<3>(IVec<3>(8, 6, 5), h / 2);
  for (auto& p : x3) p += Vec<3>(jitter(rng), jitter(rng), jitter(rng));
  std::vector<double> field3;
  std::vector<Vec<3>> gradient3;
  run_field(x3, std::vector<double>(x3.size(), 1.0), std::sqrt(3.0) * h, field3, gradient3);
  for (std::size_t p = 0; p < x3.size(); ++p) {
    EXPECT_NEAR(field3[p], 1.0, 1e-15);
    EXPECT_LT(gradient3[p].norm() * h, 1e-13);
  }
}

// Early-outs: all d̂ = 0 gives zeros; with a few damaged particles, those out of reach of any
// damage get exact zeros (skipped by bins) and every value equals the brute-force O(N²) sum.
TEST(DamageField, UndamagedRegionsAreExactlyZero) {
  const double h = 1.0, radius = std::sqrt(2.0);
  const auto x = lattice<2>(IVec<2>(60, 10), h / 2);
  std::vector<double> dhat(x.size(), 0.0);
  std::vector<double> field(3, 7.0);
  std::vector<Vec<2>> gradient;
  run_field(x, dhat, radius, field, gradient);
  ASSERT_EQ(field.size(), x.size());
  for (std::size_t p = 0; p < x.size(); ++p) {
    EXPECT_EQ(field[p], 0.0);
    EXPECT_EQ(gradient[p], Vec<2>::Zero());
  }
  dhat[0] = 1.0;  // a corner particle and one in the middle
  dhat[305] = 0.6;
  run_field(x, dhat, radius, field, gradient);
  int zero = 0;
  for (std::size_t p = 0; p < x.size(); ++p) {
    double sw = 0, sdw = 0;
    Vec<2> gw = Vec<2>::Zero(), gdw = Vec<2>::Zero();
    for (std::size_t q = 0; q < x.size(); ++q) {
      const Vec<2> r = x[p] - x[q];
      const double rbar = r.norm() / radius;
      if (rbar >= 1.0) continue;
      const Vec<2> g = -6.0 * (1.0 - rbar) / (radius * radius) * r;
      sw += damage_kernel(rbar);
      sdw += dhat[q] * damage_kernel(rbar);
      gw += g;
      gdw += dhat[q] * g;
    }
    const double value = sdw / sw;
    const Vec<2> expected = (gdw - value * gw) / sw;
    EXPECT_NEAR(field[p], value, 1e-15);
    EXPECT_NEAR((gradient[p] - expected).norm(), 0.0, 1e-14);
    if (value == 0.0) {
      ++zero;
      EXPECT_EQ(field[p], 0.0);
      EXPECT_EQ(gradient[p], Vec<2>::Zero());
    }
  }
  EXPECT_GT(zero, 500);
}

TEST(DamageField, MismatchedInputThrows) {
  const auto x = lattice<2>(IVec<2>(4, 4), 0.5);
  NeighbourLists<2> lists;
  lists.update(x, 1.0, 0.2);
  std::vector<double> field;
  std::vector<Vec<2>> gradient;
  EXPECT_THROW(
      damage_field_gradient<2>(lists, x, std::vector<double>(3, 0.0), 1.0, field, gradient),
      std::invalid_argument);
  EXPECT_THROW(
      damage_field_gradient<2>(lists, x, std::vector<double>(16, 0.0), 1.5, field, gradient),
      std::invalid_argument);  // larger than the lists' radius: pairs could be missing
}

// ---- Alg. 1 and Alg. 2 ----

TEST(DfgPartition, NodalMaximumIsOrderIndependentAndFieldRuleIsTheSign) {
  // Equal norms in different directions: the tie-break makes the fold a total order.
  std::vector<Vec<2>> candidates = {Vec<2>(3, 4), Vec<2>(-4, 3), Vec<2>(5, 0), Vec<2>(0, -5),
                                    Vec<2>(1, 1)};
  std::sort(candidates.begin(), candidates.end(), [](const Vec<2>& a, const Vec<2>& b) {
    return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
  });
  Vec<2> first = Vec<2>::Zero();
  for (const auto& c : candidates) fold_nodal_gradient<2>(c, first);
  do {
    Vec<2> node = Vec<2>::Zero();
    for (const auto& c : candidates) fold_nodal_gradient<2>(c, node);
    EXPECT_EQ(node, first);
  } while (std::next_permutation(candidates.begin(), candidates.end(),
                                 [](const Vec<2>& a, const Vec<2>& b) {
                                   return a.x() < b.x() || (a.x() == b.x() && a.y() < b.y());
                                 }));
  EXPECT_EQ(first, Vec<2>(5, 0));
  Vec<2> node = Vec<2>::Zero();
  fold_nodal_gradient<2>(Vec<2>::Zero(), node);
  EXPECT_EQ(node, Vec<2>::Zero());

  const Vec<2> gi(1.0, 0.5);
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>(2.0, -1.0), gi), 0);  // dot = 1.5
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>(1.0, -2.0), gi), 0);  // dot = 0 → field 0 (Alg. 2: ≥)
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>(-1.0, 0.0), gi), 1);
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>(-1.0, 0.0), Vec<2>::Zero()), 0);

  // CSR version: two particles, one shared node.
  std::vector<Vec<2>> gp = {Vec<2>(0, 2), Vec<2>(0, -3)};
  std::vector<std::size_t> start = {0, 2, 4};
  std::vector<std::int64_t> nodes = {0, 1, 1, 2};
  std::vector<Vec<2>> gn(3, Vec<2>(9, 9));
  nodal_damage_gradient<2>(gp, start, nodes, gn);
  EXPECT_EQ(gn[0], gp[0]);
  EXPECT_EQ(gn[1], gp[1]);
  EXPECT_EQ(gn[2], gp[1]);
  std::vector<std::uint8_t> field;
  particle_fields<2>(gp, start, nodes, gn, field);
  EXPECT_EQ(field, (std::vector<std::uint8_t>{0, 1, 0, 0}));
  nodes[3] = 3;
  EXPECT_THROW(nodal_damage_gradient<2>(gp, start, nodes, gn), std::out_of_range);
}

// Synthetic straight crack: a block with 2 particles per cell per direction and a
// one-particle-wide band of d̂ = 1 (|n·(x − c)| < s/2, s = h/2) across it, normal n at angle θ.
// Stencils are linear hats. At every interior node within h/2 of the crack plane:
//  * the nodal gradient is within `tolerance_deg` of ±n;
//  * Alg. 2 puts the particles of one side that carry a gradient in one field and those of the
//  other
//    side in the other; with the position fallback this holds for every particle of both sides.
// Nodes farther than r_p + s/2 + √D h from the plane get a zero gradient (single field).
struct CrackResult {
  double worst_deg = 0.0;
  int nodes_checked = 0;
};

template <int D>
std::array<CrackResult, 2> straight_crack(const Vec<D>& normal, const Vec<D>& centre, int cells,
                                          const std::array<double, 2>& tolerance_deg) {
  const double h = 1e-3, s = h / 2, radius = std::sqrt(double(D)) * h;
  const auto x = lattice<D>(IVec<D>::Constant(2 * cells), s);
  GridIndex<D> grid;
  grid.cell_size = h;
  grid.inverse_cell_size = 1.0 / h;
  grid.extent = IVec<D>::Constant(cells + 1);
  std::vector<std::size_t> node_start = {0};
  std::vector<std::int64_t> nodes;
  for (const auto& p : x) {
    Stencil<D> stencil;
    linear_stencil<D>(p, grid, stencil);
    for (int e = 0; e < stencil.count; ++e) nodes.push_back(stencil.node[e]);
    node_start.push_back(nodes.size());
  }
  std::vector<double> dhat;
  for (const auto& p : x) dhat.push_back(std::abs(normal.dot(p - centre)) < s / 2 ? 1.0 : 0.0);
  std::vector<double> field;
  std::vector<Vec<D>> gradient;
  run_field(x, dhat, radius, field, gradient);
  std::array<CrackResult, 2> results;
  for (const int principal : {0, 1}) {
    SCOPED_TRACE(principal ? "structure tensor" : "Alg. 1");
    std::vector<Vec<D>> nodal(static_cast<std::size_t>(grid.node_count()));
    if (principal)
      nodal_damage_gradient_principal<D>(gradient, node_start, nodes, nodal);
    else
      nodal_damage_gradient<D>(gradient, node_start, nodes, nodal);
    const double tolerance = tolerance_deg[principal];
    std::vector<std::uint8_t> plain, fallback;
    particle_fields<D>(gradient, node_start, nodes, nodal, plain);
    particle_fields<D>(gradient, node_start, nodes, nodal, x, grid, fallback);

    // Per node and side: bit f set when a particle of that side uses field f.
    std::vector<int> seen_plain[2], seen_all[2];
    for (int side = 0; side < 2; ++side) {
      seen_plain[side].assign(nodal.size(), 0);
      seen_all[side].assign(nodal.size(), 0);
    }
    CrackResult& result = results[principal];
    for (std::size_t p = 0; p < x.size(); ++p) {
      if (dhat[p] != 0.0) continue;
      const int side = normal.dot(x[p] - centre) > 0 ? 1 : 0;
      const bool has_gradient = gradient[p].squaredNorm() > 0.0;
      for (std::size_t e = node_start[p]; e < node_start[p + 1]; ++e) {
        const auto i = static_cast<std::size_t>(nodes[e]);
        if (has_gradient) seen_plain[side][i] |= 1 << plain[e];
        seen_all[side][i] |= 1 << fallback[e];
      }
    }
    const double far = radius + s / 2 + std::sqrt(double(D)) * h;
    for (std::int64_t i = 0; i < grid.node_count(); ++i) {
      const Vec<D> X = grid.position(grid.global(i));
      const double distance = std::abs(normal.dot(X - centre));
      const bool interior = X.minCoeff() >= 3 * h && X.maxCoeff() <= (cells - 3) * h;
      const auto u = static_cast<std::size_t>(i);
      if (interior && distance > far) {
        EXPECT_EQ(nodal[u], Vec<D>::Zero()) << "node " << X.transpose();
      }
      if (!interior || distance > 0.5 * h) continue;
      ++result.nodes_checked;
      const double angle = angle_between_lines_deg<D>(nodal[u], normal);
      result.worst_deg = std::max(result.worst_deg, angle);
      EXPECT_LT(angle, tolerance) << "node " << X.transpose();
      for (auto* seen : {seen_plain, seen_all}) {
        // Each side in exactly one field (1 = field 0 only, 2 = field 1 only), the two sides
        // differ.
        EXPECT_TRUE(seen[0][u] == 1 || seen[0][u] == 2) << "node " << X.transpose();
        EXPECT_TRUE(seen[1][u] == 1 || seen[1][u] == 2) << "node " << X.transpose();
        EXPECT_NE(seen[0][u], seen[1][u]) << "node " << X.transpose();
      }
    }
  }
  return results;
}

TEST(DfgPartition, StraightCrackNormalsAndSides2D) {
  std::array<double, 2> worst = {0.0, 0.0};
  for (const double degrees : {0.0, 10.0, 20.0, 30.0, 40.0, 45.0, 60.0}) {
    for (const double shift : {0.0, 0.2, 0.4}) {
      SCOPED_TRACE(::testing::Message() << degrees << "°, shift " << shift);
      const double a = degrees * std::numbers::pi / 180.0;
      const Vec<2> normal(-std::sin(a), std::cos(a));
      // Through a particle (shift 0) or between particle rows.
      const Vec<2> centre = 1e-3 * Vec<2>(12.25 + 0.37 * shift, 12.25 + shift);
      // Structure tensor: the 10°. Alg. 1 (max-norm particle) follows the band's
      // staircase: up to ~18° measured here, so it is held to 20°.
      const auto r = straight_crack<2>(normal, centre, 24, {20.0, 10.0});
      for (int k = 0; k < 2; ++k) {
        EXPECT_GT(r[k].nodes_checked, 15);
        worst[k] = std::max(worst[k], r[k].worst_deg);
      }
    }
  }
  std::printf(
      "[          ] 2D straight crack: worst nodal angle Alg. 1 %.2f deg, structure tensor %.2f "
      "deg\n",
      worst[0], worst[1]);
}

TEST(DfgPartition, StraightCrackNormalsAndSides3D) {
  std::array<double, 2> worst = {0.0, 0.0};
  for (const double degrees : {0.0, 30.0, 45.0}) {
    SCOPED_TRACE(::testing::Message() << degrees << "°");
    const double a = degrees * std::numbers::pi / 180.0, b = 0.3;  // tilted about two axes
    const Vec<3> normal(-std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b));
    const auto r = straight_crack<3>(normal, Vec<3>::Constant(6.25e-3), 12, {10.0, 10.0});
    for (int k = 0; k < 2; ++k) {
      EXPECT_GT(r[k].nodes_checked, 10);
      worst[k] = std::max(worst[k], r[k].worst_deg);
    }
  }
  std::printf(
      "[          ] 3D plane crack: worst nodal angle Alg. 1 %.2f deg, structure tensor %.2f deg\n",
      worst[0], worst[1]);
}

TEST(DfgPartition, PrincipalGradientOfKnownTensors) {
  // T = λ n ⊗ n + μ t ⊗ t with λ > μ: direction ±n, length √λ.
  const Vec<2> n = Vec<2>(3, -4) / 5.0, t(4.0 / 5.0, 3.0 / 5.0);
  const Mat<2> T = 9.0 * n * n.transpose() + 1.0 * t * t.transpose();
  const Vec<2> g = principal_gradient<2>(T);
  EXPECT_NEAR(g.norm(), 3.0, 1e-14);
  EXPECT_NEAR(std::abs(g.normalized().dot(n)), 1.0, 1e-15);
  EXPECT_EQ(principal_gradient<2>(Mat<2>::Zero()), Vec<2>::Zero());
  EXPECT_EQ(principal_gradient<2>(Mat<2>::Identity() * 4.0), Vec<2>(2.0, 0.0));  // isotropic → e_0
  const Vec<3> n3 = Vec<3>(1, 2, 2) / 3.0;
  Mat<3> T3 = 16.0 * n3 * n3.transpose() + 0.5 * Mat<3>::Identity();
  const Vec<3> g3 = principal_gradient<3>(T3);
  EXPECT_NEAR(g3.norm(), std::sqrt(16.5), 1e-12);
  EXPECT_NEAR(std::abs(g3.normalized().dot(n3)), 1.0, 1e-12);
  // Opposite particle gradients reinforce: T of {g, −g} has principal direction ±g.
  Mat<2> sum = Mat<2>::Zero();
  accumulate_gradient_tensor<2>(Vec<2>(0.0, 2.0), sum);
  accumulate_gradient_tensor<2>(Vec<2>(0.0, -2.0), sum);
  accumulate_gradient_tensor<2>(Vec<2>(0.5, 0.0), sum);
  EXPECT_NEAR(std::abs(principal_gradient<2>(sum).y()), std::sqrt(8.0), 1e-14);
  // Position fallback of Alg. 2 for a particle without gradient.
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>::Zero(), Vec<2>(0, 1), Vec<2>(0.1, -0.5)), 0);
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>::Zero(), Vec<2>(0, 1), Vec<2>(0.1, 0.5)), 1);
  EXPECT_EQ(particle_field_at_node<2>(Vec<2>(0, -1), Vec<2>(0, 1), Vec<2>(0.1, -0.5)),
            1);  // gradient wins
}

TEST(DfgPartition, GradientDecidesFieldOnlyAwayFromTheSurfacePlane) {
  // |cos(∇D̄_p, ∇D̄_i)| = 0.1 < ambiguous_gradient_cosine = 0.2: a gradient 84° from the nodal
  // direction does not decide (a junction particle's gradient along a free face's normal).
  const Vec<2> nodal(0.0, 3.0);
  EXPECT_FALSE(gradient_decides_field<2>(Vec<2>(std::sqrt(0.99), -0.1), nodal));
  EXPECT_FALSE(gradient_decides_field<2>(Vec<2>(std::sqrt(0.99), 0.1), nodal));
  // |cos| = 0.3 decides, whatever the lengths.
  EXPECT_TRUE(gradient_decides_field<2>(Vec<2>(std::sqrt(0.91), -0.3) * 5e3, nodal));
  EXPECT_TRUE(gradient_decides_field<2>(Vec<2>(0.0, -1.0), nodal));
  // A zero gradient at either end never decides.
  EXPECT_FALSE(gradient_decides_field<2>(Vec<2>::Zero(), nodal));
  EXPECT_FALSE(gradient_decides_field<2>(Vec<2>(0.0, 1.0), Vec<2>::Zero()));
}

// ---- Thread-count independence ----

TEST(DamageField, OneAndTwoThreadsGiveIdenticalResults) {
  std::mt19937 rng(21);
  auto x = random_points<2>(5000, 1.0, rng);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> dhat(x.size());
  for (auto& d : dhat) d = u(rng) < 0.3 ? u(rng) : 0.0;
  const double radius = 0.03;
  const int saved = omp_get_max_threads();
  struct Result {
    std::vector<std::size_t> start;
    std::vector<std::uint32_t> indices;
    std::vector<double> field;
    std::vector<Vec<2>> gradient;
    std::vector<Vec<2>> nodal;
    std::vector<std::uint8_t> fields;
  } result[2];
  for (int threads = 1; threads <= 2; ++threads) {
    omp_set_num_threads(threads);
    Result& r = result[threads - 1];
    NeighbourLists<2> lists;
    lists.update(x, radius, 0.2);
    auto moved = x;  // a non-rebuild step as well
    for (auto& p : moved) p += Vec<2>(0.001, -0.0005);
    EXPECT_FALSE(lists.update(moved, radius, 0.2));
    damage_field_gradient<2>(lists, moved, dhat, radius, r.field, r.gradient);
    r.start = lists.start();
    r.indices = lists.indices();
    // Stencil: the four cells' nodes of a 40 × 40 grid.
    std::vector<std::size_t> start = {0};
    std::vector<std::int64_t> nodes;
    for (const auto& p : moved) {
      const auto i = static_cast<std::int64_t>(std::clamp(p.x(), 0.0, 0.999) * 40);
      const auto j = static_cast<std::int64_t>(std::clamp(p.y(), 0.0, 0.999) * 40);
      for (const std::int64_t n :
           {i + 41 * j, i + 1 + 41 * j, i + 41 * (j + 1), i + 1 + 41 * (j + 1)})
        nodes.push_back(n);
      start.push_back(nodes.size());
    }
    r.nodal.resize(41 * 41);
    nodal_damage_gradient<2>(r.gradient, start, nodes, r.nodal);
    particle_fields<2>(r.gradient, start, nodes, r.nodal, r.fields);
  }
  omp_set_num_threads(saved);
  EXPECT_EQ(result[0].start, result[1].start);
  EXPECT_EQ(result[0].indices, result[1].indices);
  EXPECT_EQ(result[0].field, result[1].field);  // bitwise
  EXPECT_EQ(result[0].gradient, result[1].gradient);
  EXPECT_EQ(result[0].nodal, result[1].nodal);
  EXPECT_EQ(result[0].fields, result[1].fields);
}
