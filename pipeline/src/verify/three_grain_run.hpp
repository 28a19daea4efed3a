#pragma once
// One run of the three-grain crushing scene ([XLS21] §4.5) at one platen speed: the state at the
// sampled platen displacements, the top platen's force–displacement curve, temperatures and the
// energy balance (verify_three_grain.cpp uses it).
#include <string>
#include <vector>

#include "fragmpm/analysis/frame_fragments.hpp"
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/series.hpp"
#include "fragmpm/pipeline/verify_three_grain.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

struct ThreeGrainRunSpec {
  std::string scene;                  ///< embedded scene, e.g. "paper/three-grain.toml"
  std::string variant;                ///< label in tables and legends, e.g. "16 m/s"
  double platen_speed = 0;            ///< [m/s], downwards
  double cell_size = 0;               ///< [m]
  double largest_dt = 1e-8;           ///< [s]: Δt = min(this, CFL step) ([XLS21] §4.5)
  std::vector<double> displacements;  ///< platen travels to sample [m], ascending
};

/// The state at one sampled displacement.
struct ThreeGrainFrame {
  ThreeGrainSample sample;
  mpm::Particles<2> particles;             ///< all particles still in the run
  analysis::FrameFragments top_fragments;  ///< of the top grain
};

struct ThreeGrainRun {
  ThreeGrainRunSpec spec;
  std::vector<ThreeGrainFrame> frames;  ///< one per spec.displacements
  mpm::Particles<2> reference;          ///< the first state (reference configuration)
  int top_body = 0;                     ///< body id of the highest grain
  bool thermal = false;
  /// Top platen: its travel every ten steps [m] and the largest |F_y| of those ten steps [N/m].
  std::vector<double> curve_displacement, curve_force;
  double input_energy = 0.0;       ///< initial energy + wall work at the end [J/m]
  double balance_error = 0.0;      ///< unexplained energy at the end [J/m]
  mpm::EnergyAccumulators totals;  ///< the booked energies at the end [J/m]
  TimedRun timing;
  long long particles = 0;
};

/// The grain file's scene, compiled with the cell size and platen speed of `spec`. Throws
/// PipelineError when the grain file cannot be found, SceneError for a bad scene.
ThreeGrainRun run_three_grain(const ThreeGrainRunSpec& spec);

}  // namespace fragmpm::pipeline
