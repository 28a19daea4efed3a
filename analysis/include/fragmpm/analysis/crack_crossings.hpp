#pragma once
// Crack length from row crossings (docs/verification.md, `notched-bar`).
//
// The particles of one body inside a window are grouped by their reference row (centres at
// (k + ½) s in y, s the row spacing) and each row is walked in reference x. Every run of masked
// particles (no fragment: fully damaged) and every step from one fragment to another is one
// crossing of the row by a crack. The crack length per unit thickness is the number of crossings
// times s: a straight crack across n rows gives n s, two such cracks 2 n s. A crack inclined at θ
// to the rows' normal counts cos θ of its length, so the measure suits cracks that run across the
// rows, as a crack through a bar's ligament does.
#include <cstdint>

#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

/// The reference-configuration window whose rows are walked, and the body whose particles count.
struct RowWindow {
  double x_min = 0.0, x_max = 0.0;  ///< [m]
  double y_min = 0.0, y_max = 0.0;  ///< [m]
  std::int32_t body = 0;
};

/// Crack length per unit thickness [m] crossing the rows of `window`, from the fragment labels of
/// the current frame (label_fragments) and the reference positions. `row_spacing` > 0 [m].
/// Throws std::invalid_argument when the labels do not match the particles or the spacing is not
/// positive.
double crack_length_across_rows(const mpm::Particles<2>& reference, const FragmentLabels& labels,
                                const RowWindow& window, double row_spacing);

}  // namespace fragmpm::analysis
