#pragma once
// Body-fitted particles of the half cylinder of the Hertz case (docs/verification.md, `hertz`).
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::pipeline {

using Vec2 = mpm::Vec<2>;

struct CylinderParticles {
  mpm::Particles<2> particles;
  std::vector<std::int64_t> top;  ///< the highest particle of every column (the loaded face)
  double column_width = 0.0;      ///< s = h / n [m], the boundary length each top particle carries
};

/// The half-disk below y = R with centre (0, R), sampled in columns of width s = `spacing` (2R / s
/// columns; R must be a whole number of s). The lattice of the scene compiler would give the bottom
/// a flat step √(R s) wide, wider than the contact, and a staircase whose steps (s) exceed the gap
/// at the edge of contact (b² / 2R); here the lowest particle of every column where the circle is
/// flatter than 30° (|x| ≤ R/2) has its bottom edge on the chord of the circle over the column, and
/// the column's particles are the equal parallelograms (edge vectors r1 = (s, chord rise),
/// r2 = (0, Δy)) that fill it up to y = R at its centre. The gap the particles present to the flat
/// is then that of the circle to within s² / (8R) (0.3 µm at s = 0.1 mm). Steeper columns, far
/// from the contact, are filled from the top on the lattice y = R − (k + ½) s, keeping the
/// particles whose centre lies inside the circle. The layout is mirror-symmetric about x = 0.
/// Every particle gets material 0, body 0, density ρ × its area, F = I, strength +∞.
CylinderParticles half_cylinder_particles(double radius, double spacing, double density);

}  // namespace fragmpm::pipeline
