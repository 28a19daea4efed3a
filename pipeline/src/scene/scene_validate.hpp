#pragma once
// Private to the scene compiler: checks that need more than one value (geometry against the grid,
// sampled particle counts, the stability limit of a fixed time step).
#include <string>
#include <vector>

#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/pipeline/scene_shapes.hpp"
#include "scene_toml.hpp"

namespace fragmpm::pipeline::scene_detail {

/// A body as read from [[bodies]], with its table for messages.
struct BodyEntry {
  std::string name;
  BodySample sample;
  Section section;
};

/// The key whose value sets the body's extent ("radius", "max", "vertices").
std::string_view size_key(ShapeKind kind);

/// Error when any part of the shape's bounding box lies outside [grid.min, grid.max], saying by how
/// much.
void check_body_in_domain(const BodyEntry& body, const mpm::GridSpec<2>& grid);

/// Error for a body without particles (smaller than the spacing s, or hidden by earlier bodies);
/// warnings on stderr for overlapping bodies.
void check_sampling(const std::vector<BodyEntry>& bodies, const SampleResult& result,
                    double spacing);

/// Error when a fixed Δt exceeds the stability limit at C_cfl = 1 (docs/design.md "Time step").
void check_fixed_dt(const mpm::Problem<2>& problem, const Section& time);

}  // namespace fragmpm::pipeline::scene_detail
