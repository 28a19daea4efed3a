#pragma once
// Plots of a run's /series (docs/design.md), read into memory with mpm::RunFileReader::read_series:
// energy balance over time and force–displacement of each wall. Values are shown with SI prefixes
// chosen from their magnitude (µs, mJ/m, kN/m, mm).
#include <string>
#include <vector>

#include "fragmpm/analysis/plot.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"

namespace fragmpm::analysis {

/// Kinetic, strain, dissipated, friction work, contact loss, wall work, the kinetic + strain energy
/// of particles removed after leaving the domain (when any were) and balance error [J/m in 2D]
/// against time. Throws mpm::RunFileError when a series is missing, FigureError when it has no
/// rows.
PlotSpec energy_plot_spec(const mpm::RunSeries& series);

/// Each wall's reaction force magnitude |F| [N/m in 2D] against its displacement magnitude |u|;
/// a wall that never moves is plotted against the travel of the wall that moved farthest (the
/// platen pair of a crushing test: both reactions against the loading platen's travel). When no
/// wall moves at all (an impact on a fixed wall) the reactions are plotted against time instead.
/// Throws FigureError when the run has no walls or no rows.
PlotSpec force_displacement_spec(const mpm::RunSeries& series,
                                 const std::vector<std::string>& wall_names);

/// The same, reading /series of the run file at RUN_PATH first (scripts and tests).
PlotSpec energy_plot_spec(const std::string& run_path);
PlotSpec force_displacement_spec(const std::string& run_path,
                                 const std::vector<std::string>& wall_names);

}  // namespace fragmpm::analysis
