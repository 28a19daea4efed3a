#pragma once
// The extremes of a particle state that tell whether a run stayed physical: the largest volume
// ratio J = det F, how many particles more than doubled their volume, and the largest principal
// stress. Reported at the end of `fragmpm run` and in the pipeline's summary.txt; computed from a
// finished state (the end of the run or a frame), never inside the step.
#include <cstddef>
#include <string>

#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::mpm {

/// J above which a particle counts as swollen: a particle twice its initial volume is a failed
/// particle spreading out (the CPDI domain of a fully damaged particle is limited, its F is not).
inline constexpr double swollen_volume_ratio = 2.0;

struct StateExtremes {
  double largest_J = 0.0;  ///< max_p det F_p
  long long largest_J_particle = -1;
  std::size_t swollen = 0;  ///< particles with det F > swollen_volume_ratio
  /// max_p max_i |σ_i| over the principal values σ_i of the particle's Cauchy stress (in 2D the
  /// in-plane stress the run stores) [Pa]
  double largest_stress = 0.0;
  long long largest_stress_particle = -1;
};

/// Extremes over every particle of `particles` (uses F and stress). An empty state gives the
/// defaults (particle indices −1).
template <int D>
StateExtremes state_extremes(const Particles<D>& particles);

/// One line for logs and summaries: "largest J = det F 1.02 (particle 17), 0 particles with
/// J > 2, largest |principal stress| 345 MPa (particle 12)".
std::string describe(const StateExtremes& extremes);

}  // namespace fragmpm::mpm
