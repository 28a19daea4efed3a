#pragma once
// Everything the analysis reports for one frame (docs/design.md): labels, the table of resolved
// fragments, the fines apart, the number- and mass-weighted CDFs of equivalent diameter and
// roundness over the resolved fragments, and the raster cross-check.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fragmpm/analysis/distributions.hpp"
#include "fragmpm/analysis/fragment_raster.hpp"
#include "fragmpm/analysis/fragment_statistics.hpp"
#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

/// Counts and mean sizes of one frame: what the count / mean-size series over time shows.
struct FragmentSummary {
  std::size_t fragments = 0;  ///< resolved fragments
  std::size_t fines = 0;      ///< fine fragments (below the minimum particle count)
  std::int64_t fine_particles = 0;
  std::size_t masked_particles = 0;
  double mean_equivalent_diameter = 0.0;  ///< number mean over resolved fragments [m]; 0 if none
  double mass_mean_equivalent_diameter = 0.0;  ///< mass-weighted mean over resolved fragments [m]
  double largest_equivalent_diameter = 0.0;    ///< [m]
  double fragment_mass = 0.0;                  ///< total mass of the resolved fragments [kg/m]
  double fines_mass = 0.0;                     ///< [kg/m]
  double fines_area = 0.0;                     ///< [m²]
  /// Particles of the first frame that left the domain and were removed before this frame
  /// (`[grid] outside = "remove"`), and their mass [kg/m]: material neither in fragments nor in
  /// fines. Set from frame_reference; summarize_fragments leaves them zero.
  std::size_t departed_particles = 0;
  double departed_mass = 0.0;
};

/// The summary from labels and particle areas and masses alone (no hulls, no rasters): cheap enough
/// to run on every frame of a run.
FragmentSummary summarize_fragments(const mpm::Particles<2>& current, const FragmentLabels& labels);

struct FrameFragments {
  FragmentLabels labels;
  std::vector<FragmentStatistics> fragments;  ///< resolved fragments, in id order
  std::vector<FragmentStatistics> fines;      ///< fine fragments, in id order
  FragmentSummary summary;
  EmpiricalCdf equivalent_diameter;  ///< over resolved fragments, weights = fragment mass
  EmpiricalCdf roundness;
  bool has_temperature = false;
  bool raster_checked = false;
  LabellingComparison raster;      ///< valid when raster_checked
  double raster_pixel_size = 0.0;  ///< [m]
  std::string raster_note;         ///< why the check was skipped, when it was
};

/// Labels, measures and distributes the fragments of `current` (see fragments.hpp for the reference
/// configuration and the options). `raster_check` also draws the frame and compares the labellings.
FrameFragments analyze_fragments(const mpm::Particles<2>& reference,
                                 const mpm::Particles<2>& current, const FragmentOptions& options,
                                 bool raster_check = true,
                                 const StatisticsOptions& statistics = {});

}  // namespace fragmpm::analysis
