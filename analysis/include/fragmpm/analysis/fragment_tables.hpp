#pragma once
// Fragment tables: CSV files for spreadsheets and scripts, and the datasets of the run file's
// /fragments/NNNNNN/ group (docs/design.md) as in-memory columns with `units` and `description`,
// which mpm::FragmentGroupWriter stores.
//
// /fragments/NNNNNN/            attributes set by the caller (frame, time, step, options, …)
//   table/<column>              one dataset per column of the resolved-fragment table (n)
//   fines/<column>              the same columns for the fines
//   particle_fragment           fragment id per particle (N), −1 = masked
//   cdf/equivalent_diameter/    value, number_fraction, mass_fraction
//   cdf/roundness/              value, number_fraction, mass_fraction
// /fragments/series/            fragment count and mean size per frame (FragmentSeriesPoint
// columns)
#include <span>
#include <string>
#include <vector>

#include "fragmpm/analysis/distributions.hpp"
#include "fragmpm/analysis/fragment_statistics.hpp"
#include "fragmpm/analysis/frame_fragments.hpp"
#include "fragmpm/mpm/run_file_fragments.hpp"

namespace fragmpm::analysis {

/// One row of the count / mean-size series: a frame and its fragment summary.
struct FragmentSeriesPoint {
  int frame = 0;
  long long step = 0;
  double time = 0.0;                 ///< [s]
  double platen_displacement = 0.0;  ///< |u| of the platen [m]; NaN when no platen is known
  FragmentSummary summary;
};

/// One column of the fragment table: dataset name, units, description, and the CSV header
/// (name with its unit, e.g. "area_m2").
struct FragmentColumn {
  const char* name;
  const char* units;
  const char* description;
  const char* csv_header;
};

/// The columns in table order; temperature last, written only when the frame has temperatures.
const std::vector<FragmentColumn>& fragment_columns();

/// Writes the table as CSV (header line, one row per fragment). Throws std::runtime_error naming
/// the path when it cannot be written.
void write_fragment_csv(const std::string& path, std::span<const FragmentStatistics> rows,
                        bool temperature);

/// Writes a CDF as CSV with columns `value_header`, number_fraction, mass_fraction.
void write_cdf_csv(const std::string& path, const EmpiricalCdf& cdf,
                   const std::string& value_header);

/// Writes the series as CSV: frame, step, time_s, [platen_displacement_m,] fragments, fines,
/// fine_particles, masked_particles, mean / mass-weighted mean / largest equivalent diameter [m],
/// fragment and fines mass [kg/m], departed particles and their mass [kg/m] (those that left the
/// domain). The platen column appears when `platen` is true.
void write_fragment_series_csv(const std::string& path, std::span<const FragmentSeriesPoint> points,
                               bool platen);

/// The same columns as datasets (with units and descriptions) of /fragments/series.
std::vector<mpm::TableColumn> fragment_series_datasets(std::span<const FragmentSeriesPoint> points,
                                                       bool platen);

/// The datasets of a /fragments/NNNNNN group in the layout above (the caller adds the attributes).
std::vector<mpm::TableColumn> fragment_frame_datasets(const FrameFragments& frame);

}  // namespace fragmpm::analysis
