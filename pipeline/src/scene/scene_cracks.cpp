// [[cracks]]: initial cracks of phase-field materials, imposed as [KT19] §5.1 imposes its notch, by
// an initial history field on the particles along a segment (scenes/README.md).
#include "scene_cracks.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace fragmpm::pipeline::scene_detail {
namespace {

using QK = QuantityKind;

/// Distance from p to the segment a–b [m].
double segment_distance(const Vec2& p, const Vec2& a, const Vec2& b) {
  const Vec2 ab = b - a;
  const double t = std::clamp((p - a).dot(ab) / ab.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * ab)).norm();
}

}  // namespace

void apply_initial_cracks(mpm::Problem<2>& problem, const std::vector<Section>& cracks,
                          const std::map<std::string, std::vector<std::int32_t>>& bodies) {
  auto& P = problem.particles;
  for (const Section& c : cracks) {
    c.allow_only({"from", "to", "body"});
    const bool any_phase_field = std::any_of(
        problem.materials.begin(), problem.materials.end(), [](const mpm::MaterialSpec& m) {
          return std::holds_alternative<mpm::PhaseField>(m.damage);
        });
    if (!any_phase_field)
      c.fail_table(
          "expected [[cracks]] only in a scene with a damage = \"phase-field\" material (an "
          "initial "
          "crack is a history field of the phase field)");
    const Vec2 from = c.vector("from", QK::length), to = c.vector("to", QK::length);
    if (!((to - from).norm() > 0.0)) c.expected("to", "an end point different from `from`");
    std::vector<std::int32_t> chosen;
    if (c.has("body")) {
      const std::string name = c.string("body");
      const auto it = bodies.find(name);
      if (it == bodies.end())
        c.expected("body", "the name of a body or of an image / grain entry in [[bodies]]");
      chosen = it->second;
    }
    std::size_t marked = 0;
    for (std::size_t p = 0; p < P.size(); ++p) {
      const auto* law = std::get_if<mpm::PhaseField>(
          &problem.materials[static_cast<std::size_t>(P.material[p])].damage);
      if (!law) continue;
      if (!chosen.empty() && std::find(chosen.begin(), chosen.end(), P.body[p]) == chosen.end())
        continue;
      const double spacing = std::sqrt(P.volume0[p]);
      // A segment midway between two rows marks both (the tolerance takes the rounding of the
      // lattice positions out of that tie).
      if (segment_distance(P.x[p], from, to) > 0.5 * spacing * (1.0 + 1e-9)) continue;
      P.damage_history[p] =
          std::max(P.damage_history[p], initial_crack_history * law->fracture_energy / spacing);
      ++marked;
    }
    if (marked == 0)
      c.fail_table("expected a crack that crosses phase-field particles, got a segment from (" +
                   si(from.x(), "m") + ", " + si(from.y(), "m") + ") to (" + si(to.x(), "m") +
                   ", " + si(to.y(), "m") + ") that passes within half a spacing of none");
  }
}

}  // namespace fragmpm::pipeline::scene_detail
