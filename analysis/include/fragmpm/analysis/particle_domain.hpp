#pragma once
// Current area and outline of a 2D particle (plane strain, per unit thickness), as the fragment
// analysis sees them (docs/design.md).
#include <array>
#include <cstddef>

#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

/// Current area of particle p [m²]: V0 det F. This is the area the mass occupies, unaffected by the
/// shrinking of failed particles' CPDI domains ([HH17] §2.6); when F was not stored (identity) it
/// is V0. Falls back to the domain area |r1 × r2| when V0 det F is not positive (a frame without
/// V0).
double particle_area(const mpm::Particles<2>& particles, std::size_t p);

/// Local particle spacing [m]: √(particle_area) — the side of a square of the particle's area.
double particle_spacing(const mpm::Particles<2>& particles, std::size_t p);

/// The four corners x ± r1/2 ± r2/2 of the CPDI domain of particle p, in order around it. A
/// particle whose domain was not stored (r1 = r2 = 0) gets an axis-aligned square of its area.
std::array<mpm::Vec<2>, 4> particle_corners(const mpm::Particles<2>& particles, std::size_t p);

}  // namespace fragmpm::analysis
