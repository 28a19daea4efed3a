// [[loads]]: surface tractions on part of a body's boundary → mpm::TractionLoad (scenes/README.md).
#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include "scene_fracture.hpp"

namespace fragmpm::pipeline::scene_detail {
namespace {

using QK = QuantityKind;

/// [t0, t1, ...] of times, strictly increasing.
std::vector<double> time_list(const Section& s, std::string_view k) {
  const toml::node* n = s.find(k);
  if (!n) s.fail(k, "missing required key: expected an array of times");
  const toml::array* a = n->as_array();
  if (!a || a->empty()) s.expected(k, "a non-empty array of times, e.g. [\"0 us\", \"10 us\"]");
  std::vector<double> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string key = s.key(std::string(k) + "[" + std::to_string(i) + "]");
    const int line = static_cast<int>(e.source().begin.line);
    double t = 0.0;
    if (const auto* v = e.as_integer()) {
      t = static_cast<double>(v->get());
    } else if (const auto* f = e.as_floating_point()) {
      t = f->get();
    } else if (const auto* str = e.as_string()) {
      try {
        t = parse_quantity(str->get(), QK::time);
      } catch (const UnitError& err) {
        fail(s.file(), line, key, err.what());
      }
    } else {
      fail(s.file(), line, key,
           "expected a time (a number in s or a string with a unit), got " + describe(e));
    }
    if (!std::isfinite(t)) fail(s.file(), line, key, "expected a finite time, got " + describe(e));
    if (!out.empty() && !(t > out.back()))
      fail(s.file(), line, key,
           "expected times in increasing order, got " + si(t, "s") + " after " +
               si(out.back(), "s"));
    out.push_back(t);
  }
  return out;
}

void read_traction(const Section& l, mpm::TractionLoad<2>& load) {
  const toml::node* n = l.find("traction");
  if (!n)
    l.fail("traction",
           "missing required key: expected a traction [tx, ty] (pressures) or a table "
           "{ times = [...], values = [[tx, ty], ...] }");
  if (n->is_array()) {
    load.times = {0.0};
    load.tractions = {l.vector("traction", QK::pressure)};
    return;
  }
  if (!n->is_table())
    l.expected("traction",
               "a constant traction [tx, ty] (pressures) or a table { times = [...], values = "
               "[[tx, ty], ...] }");
  const Section t = l.table("traction");
  t.allow_only({"times", "values"});
  load.times = time_list(t, "times");
  load.tractions = t.point_list("values", QK::pressure);
  if (load.tractions.size() != load.times.size())
    t.fail("values", "expected one traction [tx, ty] per time (" +
                         std::to_string(load.times.size()) + "), got " +
                         std::to_string(load.tractions.size()));
}

}  // namespace

namespace {

/// The loaded boundary particles of a [[loads]] entry (`body` with `side` and/or `region`) and the
/// boundary length each carries.
void select_boundary(const Section& l, const mpm::Problem<2>& problem,
                     const std::map<std::string, std::vector<std::int32_t>>& bodies,
                     std::vector<std::int64_t>& particles, std::vector<double>& boundary_measure) {
  const std::string body = l.string("body");
  const auto found = bodies.find(body);
  if (found == bodies.end())
    l.expected(
        "body",
        "the name of a body in [[bodies]] (or of an image/grain entry, meaning all its grains)");
  std::vector<bool> in_body(problem.body_names.size(), false);
  for (std::int32_t b : found->second) in_body[static_cast<std::size_t>(b)] = true;

  if (!l.has("side") && !l.has("region"))
    l.fail("side",
           "missing required key: expected side = \"+x\" | \"-x\" | \"+y\" | \"-y\" or region = { "
           "min = [x, y], "
           "max = [x, y] } (or both)");
  std::optional<std::pair<Vec2, Vec2>> region;
  if (l.has("region")) {
    const Section r = l.table("region");
    r.allow_only({"min", "max"});
    const Vec2 lo = r.vector("min", QK::length), hi = r.vector("max", QK::length);
    if (!(hi.x() >= lo.x() && hi.y() >= lo.y()))
      r.fail("max", "expected max >= min in x and y, got max = [" + si(hi.x(), "m") + ", " +
                        si(hi.y(), "m") + "] and min = [" + si(lo.x(), "m") + ", " +
                        si(lo.y(), "m") + "]");
    region.emplace(lo, hi);
  }
  auto in_region = [&](const Vec2& x) {
    return !region || (x.x() >= region->first.x() && x.x() <= region->second.x() &&
                       x.y() >= region->first.y() && x.y() <= region->second.y());
  };

  const mpm::Particles<2>& P = problem.particles;
  // Extent of a particle's CPDI domain along each axis: |r1| + |r2| component-wise [m].
  auto extent = [&](std::size_t p) -> Vec2 {
    return P.domain[p].col(0).cwiseAbs() + P.domain[p].col(1).cwiseAbs();
  };
  if (l.has("side")) {
    const std::string side = l.string("side");
    if (side != "+x" && side != "-x" && side != "+y" && side != "-y")
      l.expected("side", "one of \"+x\", \"-x\", \"+y\", \"-y\"");
    const int axis = side[1] == 'x' ? 0 : 1;
    const double sign = side[0] == '+' ? 1.0 : -1.0;
    // The particles whose domain edge lies on the body's extreme edge on that side; each carries
    // the length of that edge, its domain's extent along the other axis.
    double extreme = -std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < P.size(); ++p)
      if (in_body[static_cast<std::size_t>(P.body[p])])
        extreme = std::max(extreme, sign * P.x[p][axis] + 0.5 * extent(p)[axis]);
    const double tolerance = 1e-6 * problem.grid.cell_size;
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (!in_body[static_cast<std::size_t>(P.body[p])] || !in_region(P.x[p])) continue;
      if (sign * P.x[p][axis] + 0.5 * extent(p)[axis] < extreme - tolerance) continue;
      particles.push_back(static_cast<std::int64_t>(p));
      boundary_measure.push_back(extent(p)[1 - axis]);
    }
  } else {
    // Boundary particles (surface flag) inside the box; each carries its domain's edge length √V₀.
    for (std::size_t p = 0; p < P.size(); ++p) {
      if (!in_body[static_cast<std::size_t>(P.body[p])] || !P.surface[p] || !in_region(P.x[p]))
        continue;
      particles.push_back(static_cast<std::int64_t>(p));
      boundary_measure.push_back(std::sqrt(std::abs(P.domain[p].determinant())));
    }
  }
  if (particles.empty())
    l.fail(region ? "region" : "side",
           "expected a load that selects at least one particle of '" + body + "', got none" +
               (l.has("side") ? " on that side inside the region"
                              : " (no boundary particle of the body lies in the region)"));
}

}  // namespace

bool is_heat_load(const Section& l) {
  return l.has("heat_flux") || l.has("film_coefficient") || l.has("ambient");
}

mpm::TractionLoad<2> read_load(const Section& l, std::size_t index, const mpm::Problem<2>& problem,
                               const std::map<std::string, std::vector<std::int32_t>>& bodies) {
  l.allow_only({"name", "body", "side", "region", "traction"});
  mpm::TractionLoad<2> load;
  load.name = l.has("name") ? l.name("name") : "load-" + std::to_string(index);
  select_boundary(l, problem, bodies, load.particles, load.boundary_measure);
  read_traction(l, load);
  return load;
}

mpm::HeatFluxLoad read_heat_load(const Section& l, std::size_t index,
                                 const mpm::Problem<2>& problem,
                                 const std::map<std::string, std::vector<std::int32_t>>& bodies) {
  l.allow_only({"name", "body", "side", "region", "heat_flux", "film_coefficient", "ambient"});
  mpm::HeatFluxLoad load;
  load.name = l.has("name") ? l.name("name") : "load-" + std::to_string(index);
  select_boundary(l, problem, bodies, load.particles, load.boundary_measure);
  if (l.has("heat_flux")) {
    if (l.has("film_coefficient") || l.has("ambient"))
      l.fail("heat_flux",
             "expected either heat_flux or film_coefficient with ambient (convection), got both");
    load.kind = mpm::ThermalWallKind::flux;
    load.flux = l.quantity("heat_flux", QK::heat_flux);
    return load;
  }
  load.kind = mpm::ThermalWallKind::convection;
  if (!l.has("film_coefficient"))
    l.fail("film_coefficient", "missing required key: convection needs film_coefficient");
  load.film_coefficient = l.quantity("film_coefficient", QK::film_coefficient);
  if (!(load.film_coefficient >= 0.0))
    l.expected("film_coefficient", "a heat transfer coefficient >= 0");
  if (!l.has("ambient"))
    l.fail("ambient", "missing required key: convection needs the ambient temperature");
  load.temperature = l.quantity("ambient", QK::temperature);
  if (!(load.temperature > 0.0)) l.expected("ambient", "an absolute temperature above 0 K");
  return load;
}

}  // namespace fragmpm::pipeline::scene_detail
