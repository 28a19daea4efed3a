// Grains → particles: counts per grain from the area, exact surface flags on
// touching grains, masses, domains, and refusals.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <opencv2/core.hpp>

#include "fragmpm/pipeline/segment.hpp"
#include "fragmpm/pipeline/segment_particles.hpp"
#include "fragmpm/pipeline/segment_synthetic.hpp"
#include "segment_test_support.hpp"

namespace fp = fragmpm::pipeline;

TEST(SegmentParticles, TouchingRectanglesHaveExactCountsAndSurfaceRings) {
  // Pixel 1 µm, h = 4 µm, 2 per cell: spacing a = 2 px, lattice points at odd pixel coordinates.
  // Grain 1: columns [10, 50) × rows [20, 50); grain 2 touches it on the right: [50, 90) × [20,
  // 50). Each is sampled by 20 × 15 lattice points; its outer ring 2·20 + 2·15 − 4 = 66 is flagged,
  // on both sides of the contact.
  cv::Mat labels = cv::Mat::zeros(70, 100, CV_32S);
  labels(cv::Rect(10, 20, 40, 30)).setTo(1);
  labels(cv::Rect(50, 20, 40, 30)).setTo(2);
  const double a = 2e-6, rho0 = 2650.0, rho1 = 3000.0;
  const auto p = fp::particles_from_labels(labels, 1e-6, {4e-6, 2}, {0, 0, 1}, {rho0, rho1});
  ASSERT_EQ(p.size(), 600u);
  std::map<int, int> count, surface;
  for (std::size_t k = 0; k < p.size(); ++k) {
    ++count[p.body[k]];
    surface[p.body[k]] += p.surface[k];
    // Flagged exactly on the ring of each 20 × 15 block.
    const int i = static_cast<int>(std::lround(p.x[k].x() / a - 0.5));
    const int j = static_cast<int>(std::lround(p.x[k].y() / a - 0.5));
    const int i0 = p.body[k] == 0 ? 5 : 25;
    const int j0 = 10;  // rows [20, 50) are y ∈ [20, 50) µm from the bottom of the 70-row image
    const bool ring = i == i0 || i == i0 + 19 || j == j0 || j == j0 + 14;
    EXPECT_EQ(p.surface[k], ring ? 1 : 0) << "particle at lattice " << i << "," << j;
    EXPECT_DOUBLE_EQ(p.volume0[k], a * a);
    EXPECT_DOUBLE_EQ(p.mass[k], (p.body[k] == 0 ? rho0 : rho1) * a * a);
    EXPECT_EQ(p.material[k], p.body[k]);
    EXPECT_EQ(p.domain[k], (fragmpm::mpm::Mat<2>::Identity() * a));
    EXPECT_EQ(p.F[k], (fragmpm::mpm::Mat<2>::Identity()));
    EXPECT_EQ(p.v[k], (fragmpm::mpm::Vec<2>::Zero()));
  }
  EXPECT_EQ(count[0], 300);
  EXPECT_EQ(count[1], 300);
  EXPECT_EQ(surface[0], 66);
  EXPECT_EQ(surface[1], 66);
}

TEST(SegmentParticles, ParticlesPerGrainMatchTheGrainArea) {
  const fp::SyntheticImage d = fp::synthetic_irregular(9);
  fp::SegmentOptions o = fp::testing::micrometre_options("irregular");
  const fp::Segmentation s = fp::segment(d.image, o);
  // Particle spacings 2, 1 and 1.5 pixels on grains of 1500 – 6500 px².
  for (const fp::ParticleSampling sampling :
       {fp::ParticleSampling{4e-6, 2}, fp::ParticleSampling{3e-6, 3},
        fp::ParticleSampling{6e-6, 4}}) {
    const int n = sampling.particles_per_cell;
    const auto p = fp::particles_from_labels(s.table.labels, s.pixel_size, sampling,
                                             fp::material_of_labels(s.table), {2650.0});
    const double a = sampling.cell_size / n;
    std::vector<int> count(s.table.grains.size(), 0);
    for (const auto b : p.body) ++count[static_cast<std::size_t>(b)];
    for (const fp::Grain& g : s.table.grains) {
      const double expected = g.shape.area / (a * a);
      EXPECT_NEAR(count[static_cast<std::size_t>(g.label - 1)] / expected, 1.0, 0.02)
          << "grain " << g.label << " with " << expected << " expected particles, n = " << n;
    }
  }
}

TEST(SegmentParticles, SurfaceFlagsMarkExactlyTheBoundaryOfDisks) {
  // Touching pairs: a particle is flagged iff one of its 8 lattice neighbours samples another
  // grain, the background or lies outside; check every flagged particle is within one lattice
  // diagonal of a pixel of another label and every unflagged one is not.
  const fp::SyntheticImage d = fp::synthetic_touching_pairs();
  const fp::Segmentation s = fp::segment(d.image, fp::testing::micrometre_options("pairs"));
  const double a = 3e-6;  // h = 6 µm, 2 per cell
  const auto p = fp::particles_from_labels(s.table.labels, 1e-6, {6e-6, 2},
                                           fp::material_of_labels(s.table), {2650.0});
  const cv::Mat& L = s.table.labels;
  auto label_at = [&](double x, double y) {  // physical → pixel
    const int col = static_cast<int>(std::floor(x / 1e-6)),
              row = L.rows - 1 - static_cast<int>(std::floor(y / 1e-6));
    if (col < 0 || row < 0 || col >= L.cols || row >= L.rows) return 0;
    return L.at<int>(row, col);
  };
  std::size_t flagged = 0, contact_flags = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    const int own = p.body[k] + 1;
    bool near_other = false, near_grain = false;
    for (int di = -1; di <= 1; ++di)
      for (int dj = -1; dj <= 1; ++dj) {
        const int l = label_at(p.x[k].x() + di * a, p.x[k].y() + dj * a);
        near_other = near_other || l != own;
        near_grain = near_grain || (l != own && l != 0);
      }
    EXPECT_EQ(p.surface[k] == 1, near_other) << "particle " << k;
    flagged += p.surface[k];
    contact_flags += near_grain && p.surface[k];
  }
  EXPECT_GT(flagged, 0u);
  // Both sides of every one of the six contacts carry flags.
  EXPECT_GE(contact_flags, 12u);
}

TEST(SegmentParticles, AutoCellSizeAndRefusals) {
  const fp::SyntheticImage d = fp::synthetic_disks();
  const fp::Segmentation s = fp::segment(d.image, fp::testing::micrometre_options("disks"));
  // Median equivalent diameter of radii 10 … 42 (twelve disks) is that of r = 28 → 56 µm / 8 = 7
  // µm.
  EXPECT_DOUBLE_EQ(fp::auto_cell_size(s.table, 1e-6), 7e-6);
  const auto m = fp::material_of_labels(s.table);
  EXPECT_THROW(fp::particles_from_labels(s.table.labels, 1e-6, {0.0, 2}, m, {2650.0}),
               fp::SegmentInputError);
  EXPECT_THROW(fp::particles_from_labels(s.table.labels, 1e-6, {1e-5, 0}, m, {2650.0}),
               fp::SegmentInputError);
  EXPECT_THROW(fp::particles_from_labels(s.table.labels, 1e-6, {1e-5, 2}, m, {}),
               fp::SegmentInputError);
  EXPECT_THROW(fp::particles_from_labels(s.table.labels, 1e-6, {1e-5, 2}, {0}, {2650.0}),
               fp::SegmentInputError);
}
