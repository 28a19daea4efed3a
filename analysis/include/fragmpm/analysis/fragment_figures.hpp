#pragma once
// Figures of the fragment analysis (as [XLS21] Fig. 17-18): CDFs of equivalent diameter and
// roundness with one curve per analysed frame, and fragment count and mean size against time.
#include <span>
#include <string>
#include <vector>

#include "fragmpm/analysis/distributions.hpp"
#include "fragmpm/analysis/fragment_tables.hpp"
#include "fragmpm/analysis/plot.hpp"

namespace fragmpm::analysis {

/// One curve of a CDF figure: its legend label and distribution.
struct CdfCurve {
  std::string label;  ///< e.g. "t = 20 µs, u = 0.2 mm"
  EmpiricalCdf cdf;
};

enum class CdfQuantity { equivalent_diameter, roundness };
enum class CdfWeighting { number, mass };

/// CDF plot with a staircase curve per entry of `curves` (curves without fragments are left out).
/// Equivalent diameters are shown with an SI prefix (µm, mm). Throws FigureError when no curve has
/// a point.
PlotSpec cdf_plot_spec(std::span<const CdfCurve> curves, CdfQuantity quantity,
                       CdfWeighting weighting);

/// Resolved fragments and fines against time.
PlotSpec fragment_count_spec(std::span<const FragmentSeriesPoint> points);

/// Number mean, mass-weighted mean and largest equivalent diameter against time (frames without
/// resolved fragments are left out). Throws FigureError when no frame has a fragment.
PlotSpec fragment_size_spec(std::span<const FragmentSeriesPoint> points);

}  // namespace fragmpm::analysis
