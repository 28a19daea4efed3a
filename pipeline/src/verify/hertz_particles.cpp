// Body-fitted particles of the Hertz half cylinder (hertz_particles.hpp).
#include "hertz_particles.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace fragmpm::pipeline {

namespace {

/// Height of the circle's lower arc above its lowest point at distance x from its axis [m].
double arc_height(double radius, double x) {
  return radius - std::sqrt(std::max(0.0, radius * radius - x * x));
}

/// Columns where the circle is flatter than 30° (x ≤ R/2) get chord-fitted bottoms.
constexpr double fitted_fraction = 0.5;

}  // namespace

CylinderParticles half_cylinder_particles(double radius, double spacing, double density) {
  const double columns_real = radius / spacing;
  const long long columns = std::llround(columns_real);
  if (columns < 1 || std::abs(columns_real - static_cast<double>(columns)) > 1e-9 * columns_real)
    throw std::invalid_argument(
        "half_cylinder_particles: the radius must be a whole number of "
        "particle spacings");
  CylinderParticles out;
  out.column_width = spacing;
  mpm::Particles<2>& P = out.particles;
  auto add = [&](const Vec2& x, const Vec2& r1, const Vec2& r2, bool surface) {
    const std::size_t p = P.size();
    P.resize(p + 1);
    P.x[p] = x;
    P.domain[p].col(0) = r1;
    P.domain[p].col(1) = r2;
    P.volume0[p] = std::abs(r1.x() * r2.y() - r1.y() * r2.x());
    P.mass[p] = density * P.volume0[p];
    P.surface[p] = surface ? 1 : 0;
    P.strength[p] = std::numeric_limits<double>::infinity();
    return static_cast<std::int64_t>(p);
  };
  for (long long i = -columns; i < columns; ++i) {
    const double left = static_cast<double>(i) * spacing, right = left + spacing;
    const double centre = left + 0.5 * spacing;
    if (std::max(std::abs(left), std::abs(right)) <= fitted_fraction * radius) {
      // Chord-fitted column: the bottom edge runs from (left, y(left)) to (right, y(right)).
      const double y_left = arc_height(radius, left), y_right = arc_height(radius, right);
      const double rise = y_right - y_left;
      const double bottom = 0.5 * (y_left + y_right);  // chord height at the column centre
      const double height = radius - bottom;
      const long long rows = std::max(1LL, std::llround(height / spacing));
      const double row_height = height / static_cast<double>(rows);
      const Vec2 r1(spacing, rise), r2(0.0, row_height);
      std::int64_t last = -1;
      for (long long k = 0; k < rows; ++k)
        last = add(Vec2(centre, bottom + (static_cast<double>(k) + 0.5) * row_height), r1, r2,
                   k == 0 || k + 1 == rows);
      out.top.push_back(last);
    } else {
      // Lattice column from the top face down, centres inside the circle.
      const Vec2 r1(spacing, 0.0), r2(0.0, spacing);
      const double lowest = arc_height(radius, centre);
      bool first = true;
      for (long long k = 0;; ++k) {
        const double y = radius - (static_cast<double>(k) + 0.5) * spacing;
        if (y <= lowest) break;
        const std::int64_t p = add(Vec2(centre, y), r1, r2, first || y - spacing <= lowest);
        if (first) out.top.push_back(p);
        first = false;
      }
    }
  }
  return out;
}

}  // namespace fragmpm::pipeline
