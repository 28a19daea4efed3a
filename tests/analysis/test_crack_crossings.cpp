// Crack length from row crossings (analysis/crack_crossings.hpp) on lattices whose cracks are
// known: the length must be the number of rows each crack crosses times the row spacing.
#include <gtest/gtest.h>

#include <cstdint>
#include <stdexcept>

#include "fragmpm/analysis/crack_crossings.hpp"
#include "fragmpm/analysis/fragments.hpp"

namespace fa = fragmpm::analysis;
namespace fm = fragmpm::mpm;

namespace {

constexpr double kSpacing = 0.5e-3;  // [m]
constexpr int kColumns = 12;
constexpr int kRows = 8;

/// A bar of kColumns × kRows particles (centres at (i + ½) s, (j + ½) s), undeformed, body 0.
fm::Particles<2> bar() {
  fm::Particles<2> P;
  for (int j = 0; j < kRows; ++j)
    for (int i = 0; i < kColumns; ++i) {
      const std::size_t p = P.size();
      P.resize(p + 1);
      P.x[p] = {(i + 0.5) * kSpacing, (j + 0.5) * kSpacing};
      P.volume0[p] = kSpacing * kSpacing;
      P.mass[p] = 2300.0 * kSpacing * kSpacing;
      P.domain[p] = fm::Mat<2>::Identity() * kSpacing;
      P.body[p] = 0;
    }
  return P;
}

std::size_t index(int column, int row) {
  return static_cast<std::size_t>(row * kColumns + column);
}

/// The whole bar as the window.
fa::RowWindow whole_bar() {
  return {0.0, kColumns * kSpacing, 0.0, kRows * kSpacing, 0};
}

double crack_length(const fm::Particles<2>& reference, const fm::Particles<2>& current,
                    const fa::RowWindow& window = whole_bar()) {
  return fa::crack_length_across_rows(reference, fa::label_fragments(reference, current), window,
                                      kSpacing);
}

}  // namespace

TEST(CrackCrossings, IntactBarHasNoCrack) {
  const fm::Particles<2> reference = bar();
  EXPECT_EQ(crack_length(reference, reference), 0.0);
}

TEST(CrackCrossings, OneFailedColumnIsOneCrackAcrossEveryRow) {
  const fm::Particles<2> reference = bar();
  fm::Particles<2> current = reference;
  for (int j = 0; j < kRows; ++j) current.damage[index(5, j)] = 1.0;
  EXPECT_NEAR(crack_length(reference, current), kRows * kSpacing, 1e-15);
  // Two adjacent failed columns are still one band, one crack.
  for (int j = 0; j < kRows; ++j) current.damage[index(6, j)] = 1.0;
  EXPECT_NEAR(crack_length(reference, current), kRows * kSpacing, 1e-15);
}

TEST(CrackCrossings, TwoSeparateCracksCountTwice) {
  const fm::Particles<2> reference = bar();
  fm::Particles<2> current = reference;
  for (int j = 0; j < kRows; ++j) {
    current.damage[index(3, j)] = 1.0;
    current.damage[index(8, j)] = 1.0;
  }
  EXPECT_NEAR(crack_length(reference, current), 2 * kRows * kSpacing, 1e-15);
}

TEST(CrackCrossings, PartialCrackCountsTheRowsItCrosses) {
  const fm::Particles<2> reference = bar();
  fm::Particles<2> current = reference;
  for (int j = 0; j < 3; ++j) current.damage[index(5, j)] = 1.0;
  EXPECT_NEAR(crack_length(reference, current), 3 * kSpacing, 1e-15);
}

TEST(CrackCrossings, OpenedFacesCountWithoutFullDamage) {
  // The right half moved 2 spacings away, its particles only partly damaged: the fragments'
  // bonds are cut by the opening, so every row is crossed once.
  const fm::Particles<2> reference = bar();
  fm::Particles<2> current = reference;
  for (std::size_t p = 0; p < current.size(); ++p) {
    current.damage[p] = 0.5;
    if (reference.x[p][0] > 6 * kSpacing) current.x[p][0] += 2 * kSpacing;
  }
  EXPECT_NEAR(crack_length(reference, current), kRows * kSpacing, 1e-15);
}

TEST(CrackCrossings, WindowAndBodyLimitWhatCounts) {
  const fm::Particles<2> reference = bar();
  fm::Particles<2> current = reference;
  for (int j = 0; j < kRows; ++j) current.damage[index(2, j)] = 1.0;
  // The window covers columns 4-11 and rows 2-7 only: the crack in column 2 is outside it.
  const fa::RowWindow right{4 * kSpacing, kColumns * kSpacing, 2 * kSpacing, kRows * kSpacing, 0};
  EXPECT_EQ(crack_length(reference, current, right), 0.0);
  fa::RowWindow other_body = whole_bar();
  other_body.body = 1;
  EXPECT_EQ(crack_length(reference, current, other_body), 0.0);
}

TEST(CrackCrossings, RejectsMismatchedLabelsAndSpacing) {
  const fm::Particles<2> reference = bar();
  fa::FragmentLabels labels = fa::label_fragments(reference, reference);
  EXPECT_THROW(fa::crack_length_across_rows(reference, labels, whole_bar(), 0.0),
               std::invalid_argument);
  labels.fragment.pop_back();
  EXPECT_THROW(fa::crack_length_across_rows(reference, labels, whole_bar(), kSpacing),
               std::invalid_argument);
}
