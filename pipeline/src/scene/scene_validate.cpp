// Scene checks across values: bodies against the grid, particle counts, fixed time step.
#include "scene_validate.hpp"

#include <algorithm>
#include <iostream>

#include "fragmpm/mpm/solver.hpp"

namespace fragmpm::pipeline::scene_detail {

std::string_view size_key(ShapeKind kind) {
  switch (kind) {
    case ShapeKind::disk:
      return "radius";
    case ShapeKind::box:
      return "max";
    case ShapeKind::polygon:
      return "vertices";
  }
  return "shape";
}

void check_body_in_domain(const BodyEntry& body, const mpm::GridSpec<2>& grid) {
  const auto [lo, hi] = bounding_box(body.sample.shape);
  static const char* axis[2] = {"x", "y"};
  double worst = 0.0;
  std::string where, key;
  for (int d = 0; d < 2; ++d) {
    if (grid.min[d] - lo[d] > worst) {
      worst = grid.min[d] - lo[d];
      where = "below grid.min in " + std::string(axis[d]) + " (" + si(lo[d], "m") + " < " +
              si(grid.min[d], "m") + ")";
      key = body.sample.shape.kind == ShapeKind::box ? "min" : "";
    }
    if (hi[d] - grid.max[d] > worst) {
      worst = hi[d] - grid.max[d];
      where = "above grid.max in " + std::string(axis[d]) + " (" + si(hi[d], "m") + " > " +
              si(grid.max[d], "m") + ")";
      key = body.sample.shape.kind == ShapeKind::box ? "max" : "";
    }
  }
  // Round-off in "centre − radius" must not count as sticking out.
  if (worst <= 1e-9 * grid.cell_size) return;
  if (key.empty()) key = body.sample.shape.kind == ShapeKind::disk ? "center" : "vertices";
  body.section.fail(key,
                    "expected body '" + body.name +
                        "' inside the grid domain [grid.min, grid.max], got a shape that extends " +
                        si(worst, "m") + " outside it, " + where);
}

void check_sampling(const std::vector<BodyEntry>& bodies, const SampleResult& result,
                    double spacing) {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    const BodyEntry& body = bodies[b];
    if (result.count[b] > 0) continue;
    if (result.in_shape[b] == 0)
      body.section.fail(size_key(body.sample.shape.kind),
                        "expected a body that holds at least one particle, got an empty body: '" +
                            body.name +
                            "' is smaller than the particle spacing h/n = " + si(spacing, "m") +
                            " (no lattice point grid.min + (i + 1/2) h/n falls inside it)");
    std::string hiders;
    for (std::size_t a = 0; a < b; ++a)
      if (result.overlap[b][a] > 0) hiders += (hiders.empty() ? "'" : ", '") + bodies[a].name + "'";
    body.section.fail_table(
        "expected a body that holds at least one particle, got an empty body: all " +
        std::to_string(result.in_shape[b]) + " particle sites of '" + body.name +
        "' lie inside earlier bodies (" + hiders + ")");
  }
  for (std::size_t b = 0; b < bodies.size(); ++b)
    for (std::size_t a = 0; a < b; ++a)
      if (result.overlap[b][a] > 0)
        std::cerr << bodies[b].section.file() << ":" << bodies[b].section.line()
                  << ": warning: body '" << bodies[b].name << "' overlaps body '" << bodies[a].name
                  << "' at " << result.overlap[b][a] << " particle sites; they belong to '"
                  << bodies[a].name << "' (earlier in the file)\n";
}

void check_fixed_dt(const mpm::Problem<2>& problem, const Section& time) {
  if (problem.time.fixed_dt <= 0.0) return;
  const double limit = mpm::stable_time_step<2>(problem, problem.particles, 1.0);
  if (problem.time.fixed_dt > limit)
    time.fail("dt", "expected a time step within the stability limit: dt = " +
                        si(problem.time.fixed_dt, "s") + " exceeds the stability limit " +
                        si(limit, "s") + " (C_cfl = 1)");
}

}  // namespace fragmpm::pipeline::scene_detail
