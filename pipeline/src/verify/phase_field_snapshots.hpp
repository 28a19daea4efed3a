#pragma once
// The phase field of a verification run at the time points of a paper's figure, kept during the
// run and written as one panel per time point, so the result can be laid beside the paper's.
#include <string>
#include <vector>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/solver.hpp"

namespace fragmpm::pipeline {

struct PhaseFieldSnapshots {
  std::vector<double> wanted;  ///< [s], ascending: the figure's time points
  std::vector<mpm::Particles<2>> frames;
  std::vector<double> times;  ///< [s], when each frame was taken
};

/// Snapshots at `wanted_us` [µs] (ascending).
PhaseFieldSnapshots phase_field_snapshots(const std::vector<double>& wanted_us);

/// Copies the particles when the solver's time has reached the next wanted time point (within
/// 1 ns). Call it before the first step (for t = 0) and after every observed step; the runs that
/// use it observe at a cadence that lands on every wanted time.
void take_snapshot(PhaseFieldSnapshots& snapshots, const mpm::Solver<2>& solver);

/// The same for a frame read back from a run file, `frame` holding each particle's current domain.
void take_snapshot(PhaseFieldSnapshots& snapshots, mpm::Particles<2> frame, double time);

/// Writes `png_path` (its folder is created): the phase field d in [0, 1] of every frame taken,
/// three panels to a row, each titled with `title` and its time. Prints the path to stderr. Does
/// nothing when no frame was taken.
void write_phase_field_panels(const PhaseFieldSnapshots& snapshots, const std::string& png_path,
                              const std::string& title);

}  // namespace fragmpm::pipeline
