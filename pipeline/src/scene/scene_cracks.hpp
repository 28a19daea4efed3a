#pragma once
// Private to the scene compiler: [[cracks]], initial cracks of phase-field materials imposed as a
// history field on the particles along a segment ([KT19] §5.1). Format: scenes/README.md.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "fragmpm/mpm/problem.hpp"
#include "scene_toml.hpp"

namespace fragmpm::pipeline::scene_detail {

/// The history a [[cracks]] entry gives the particles it crosses, in units of G_c / s (s the
/// particle spacing): the line then carries d = B/(1 + B) = 0.999 at every resolution, since a
/// line of history H and width s balances the crack profile's flux when H s = G_c d / (1 − d).
inline constexpr double initial_crack_history = 1e3;

/// Sets damage_history = initial_crack_history × G_c / s on every phase-field particle (of `body`
/// when given, a body name or an image / grain entry meaning all its grains) whose centre lies
/// within half a particle spacing s = √V₀ of the segment from–to. `bodies` maps names to body ids.
/// Errors name the entry's key: no phase-field material in the scene, a segment of zero length, an
/// unknown body, a segment that crosses no phase-field particle.
void apply_initial_cracks(mpm::Problem<2>& problem, const std::vector<Section>& cracks,
                          const std::map<std::string, std::vector<std::int32_t>>& bodies);

}  // namespace fragmpm::pipeline::scene_detail
