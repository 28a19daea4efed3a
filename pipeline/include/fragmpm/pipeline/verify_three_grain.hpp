#pragma once
// Three-grain crushing ([XLS21] §4.5, Table 4, Fig. 15-25): what `fragmpm verify three-grain`
// measures on the top grain at each platen displacement, and the published trends it checks.
#include <string>
#include <vector>

#include "fragmpm/analysis/frame_fragments.hpp"
#include "fragmpm/pipeline/verify.hpp"

namespace fragmpm::pipeline {

/// One row of three-grain/summary.csv: one loading rate at one platen displacement.
struct ThreeGrainSample {
  std::string variant;              ///< "8 m/s", "16 m/s isothermal", …
  double platen_speed = 0.0;        ///< [m/s]
  double displacement = 0.0;        ///< platen travel [m]
  double time = 0.0;                ///< [s]
  long long fragments = 0;          ///< resolved fragments of the top grain
  long long fines = 0;              ///< fragments below the minimum particle count
  double mean_diameter = 0.0;       ///< number mean of d_eq over resolved fragments [m]
  double largest_diameter = 0.0;    ///< [m]
  double diameter_deviation = 0.0;  ///< sample standard deviation of d_eq (n − 1; 0 for n < 2) [m]
  double mean_roundness = 0.0;      ///< number mean over resolved fragments [1]
  double peak_force = 0.0;          ///< largest |F_y| on the top platen so far [N/m]
  double largest_temperature_rise = 0.0;  ///< max over particles and time so far of θ − θ₀ [K]
};

/// Fills the fragment columns of `sample` (fragments, fines, mean, largest and standard deviation
/// of d_eq, mean roundness) from the fragments of one frame of the top grain; the other members are
/// left as they are. A frame without resolved fragments gives zeros.
void summarize_top_grain(const analysis::FrameFragments& frame, ThreeGrainSample& sample);

/// Writes the samples as CSV with a header line (SI units, named in the header).
void write_three_grain_summary(const std::string& path, const std::vector<ThreeGrainSample>& rows);

/// `fragmpm verify three-grain`: the coupled runs at 8, 16 and 80 m/s and the isothermal run at
/// 16 m/s; quick: h = 0.2 mm to 0.8 mm of platen travel, otherwise h = 0.1 mm to 4 mm. Writes the
/// figures and summary.csv under DIR/three-grain/ and returns the trend and energy checks.
std::vector<VerifyRow> verify_three_grain(const VerifyOptions& options);

}  // namespace fragmpm::pipeline
