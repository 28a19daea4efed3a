#pragma once
// Simple 2D shapes (disk, box, polygon) and their sampling into material points on the regular
// sub-cell lattice of a grid (docs/design.md). Used by the scene compiler; exposed for tests and
// for other body sources that want the same particle conventions.
#include <cstddef>
#include <utility>
#include <vector>

#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::pipeline {

using Vec2 = mpm::Vec<2>;

enum class ShapeKind { disk, box, polygon };

struct Shape {
  ShapeKind kind = ShapeKind::box;
  Vec2 center = Vec2::Zero();  ///< disk [m]
  double radius = 0.0;         ///< disk [m]
  double inner_radius = 0.0;   ///< disk: a ring when > 0, the hole concentric [m]
  Vec2 min = Vec2::Zero();     ///< box lower corner [m]
  Vec2 max = Vec2::Zero();     ///< box upper corner [m]
  std::vector<Vec2> vertices;  ///< polygon, either orientation [m]
};

/// Closed containment test (points on the boundary count as inside).
bool contains(const Shape& shape, const Vec2& p);
/// Axis-aligned bounding box of the shape: {lower corner, upper corner}.
std::pair<Vec2, Vec2> bounding_box(const Shape& shape);
/// Area enclosed by a polygon (absolute value of the shoelace sum) [m^2].
double polygon_area(const std::vector<Vec2>& vertices);
/// Indices (a, b) of two polygon edges that cross or touch although they are not neighbours, or
/// that fold back on each other; edge k joins vertex k to vertex k+1. {-1, -1} when the polygon is
/// simple.
std::pair<int, int> polygon_self_intersection(const std::vector<Vec2>& vertices);

/// A body to sample: shape, material index, initial rigid motion.
struct BodySample {
  Shape shape;
  int material = 0;
  Vec2 velocity = Vec2::Zero();  ///< [m/s]
  double angular_velocity =
      0.0;  ///< ω [rad/s], counter-clockwise about the centroid of the body's particles
};

struct SampleResult {
  mpm::Particles<2> particles;
  std::vector<std::size_t> count;     ///< particles per body
  std::vector<std::size_t> in_shape;  ///< lattice points inside each shape (claimed or not)
  /// overlap[b][a] (a < b): lattice points inside body b that went to the earlier body a.
  std::vector<std::vector<std::size_t>> overlap;
};

/// A symmetry plane of the scene (a roller wall): the material continues as its mirror image
/// beyond it. point: a point on the plane [m]; normal: unit normal towards the material side.
struct MirrorPlane {
  Vec2 point = Vec2::Zero();
  Vec2 normal = Vec2::UnitX();
};

/// Fills bodies with particles, n = particles_per_cell per direction, spacing s = h/n on the
/// lattice x = grid.min + (i + 1/2) s. A lattice point belongs to the first body (in order) whose
/// shape contains it. Each particle: F = I, CPDI domain diag(s, s), volume0 = s² (per unit
/// thickness), mass = ρ volume0, v = v0 + ω × (x − centroid), strength = +inf, surface = 1 when any
/// of its eight lattice neighbours belongs to another body or to none. A neighbour beyond a mirror
/// plane stands for its mirror image: it counts as present when the image point lies in the same
/// body, so a body's face on a symmetry plane is not a surface (the full body continues across it).
SampleResult sample_bodies(const std::vector<BodySample>& bodies,
                           const std::vector<mpm::MaterialSpec>& materials,
                           const mpm::GridSpec<2>& grid, int particles_per_cell,
                           const std::vector<MirrorPlane>& mirrors = {});

}  // namespace fragmpm::pipeline
