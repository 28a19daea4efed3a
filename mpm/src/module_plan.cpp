// Which modules a scene's step runs, and why: fixed once at setup from the scene and logged by
// `fragmpm run` (and written to /meta), so a reader of a run knows what physics it contains.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/mpm/wave_speed.hpp"

namespace fragmpm::mpm {

template <int D>
bool partitioning_active(const Problem<D>& problem) {
  if (problem.contact.partitioning == Partitioning::off) return false;
  if (problem.contact.partitioning == Partitioning::bodies) return true;
  if (problem.body_names.size() > 1) return true;
  for (const auto& m : problem.materials)
    if (m.damages()) return true;
  return false;
}

namespace {

/// Whether a wall's velocity history ever has a component along its normal: such a wall sweeps
/// through the grid instead of standing on one node line.
template <int D>
bool moves_along_normal(const WallSpec<D>& wall) {
  const VelocityHistory<D>& v = wall.velocity;
  const double scale = std::abs(v.from.dot(wall.normal)) + std::abs(v.to.dot(wall.normal)) +
                       std::abs(v.amplitude.dot(wall.normal));
  return scale > 0.0;
}

/// The walls line of the module log. A moving contact wall without the gap test acts on the node
/// rows its plane has passed, so the material feels it advance one cell at a time (walls.cpp);
/// the log names such walls, since the platen force then comes in pulses once per cell.
template <int D>
std::string walls_reason(const std::vector<WallSpec<D>>& walls) {
  if (walls.empty()) return "no walls in the scene";
  std::string reason = std::to_string(walls.size()) + " rigid wall(s)";
  std::string gap_tested, stepping;
  for (const WallSpec<D>& w : walls) {
    if (w.kind != WallKind::contact) continue;
    if (w.gap_test)
      gap_tested += (gap_tested.empty() ? "'" : ", '") + w.name + "'";
    else if (moves_along_normal(w))
      stepping += (stepping.empty() ? "'" : ", '") + w.name + "'";
  }
  if (!gap_tested.empty())
    reason += "; " + gap_tested + " touch(es) the material by its position (gap_test)";
  if (!stepping.empty())
    reason += "; moving contact wall(s) " + stepping +
              " without gap_test act on the node rows they have passed, so they advance one "
              "cell at a time";
  return reason;
}

}  // namespace

template <int D>
std::vector<ModuleDecision> plan_modules(const Problem<D>& problem) {
  std::vector<ModuleDecision> plan;
  const char* shape = "linear";
  switch (problem.grid.shape_function) {
    case ShapeFunctionKind::cpdi:
      shape = "CPDI";
      break;
    case ShapeFunctionKind::ugimp:
      shape = "uGIMP";
      break;
    case ShapeFunctionKind::bspline2:
      shape = "quadratic B-spline";
      break;
    case ShapeFunctionKind::linear:
      break;
  }
  // The elastic law follows the degradation: the Hencky split needs the Hencky energy.
  bool hencky = false, neo_hookean = false;
  for (const MaterialSpec& m : problem.materials)
    (elastic_law(m) == ElasticLaw::hencky ? hencky : neo_hookean) = true;
  const char* elasticity = hencky && neo_hookean ? "neo-Hookean and Hencky bodies"
                           : hencky              ? "Hencky bodies (phase field or hencky-spectral)"
                                                 : "neo-Hookean bodies";
  plan.push_back({"mechanics", true,
                  std::string("explicit update-stress-last MPM with ") + shape +
                      " shape functions, " + elasticity +
                      (D == 3                 ? ""
                       : problem.plane_stress ? ", plane stress ([physics] plane = \"stress\")"
                                              : ", plane strain")});
  plan.push_back({"walls", !problem.walls.empty(), walls_reason(problem.walls)});
  plan.push_back({"loads", !problem.loads.empty(),
                  problem.loads.empty()
                      ? "no traction loads"
                      : std::to_string(problem.loads.size()) + " traction load(s)"});
  plan.push_back({"gravity", problem.gravity.squaredNorm() > 0.0,
                  problem.gravity.squaredNorm() > 0.0 ? "gravity set in [physics]" : "no gravity"});
  std::vector<std::string> damaging;
  for (const auto& m : problem.materials)
    if (m.damages()) damaging.push_back(m.name);
  std::string damage_reason = "no damage law in the scene";
  if (!damaging.empty()) {
    damage_reason = "damage law on material(s)";
    for (const auto& name : damaging) damage_reason += " '" + name + "'";
  }
  plan.push_back({"damage", !damaging.empty(), damage_reason});
  std::string flowing;
  for (const auto& m : problem.materials)
    if (m.crushed_friction_angle > 0.0) {
      char angle[32];
      std::snprintf(angle, sizeof angle, "%.1f deg", m.crushed_friction_angle * 180.0 / M_PI);
      flowing += (flowing.empty() ? "" : ", ") + m.name + " (" + angle + ")";
    }
  plan.push_back({"crushed flow", !flowing.empty(),
                  flowing.empty()
                      ? "no crushed_friction_angle: failed material keeps its compressive energy"
                      : "failed particles flow as a cohesionless Mohr-Coulomb solid: " + flowing});
  std::string phase_field_reason;
  for (const auto& m : problem.materials)
    if (const auto* law = std::get_if<PhaseField>(&m.damage)) {
      char text[160];
      std::snprintf(text, sizeof text, "%s'%s' (l0 = %.4g m, G_c = %.4g J/m2, k_f = %.3g%s)",
                    phase_field_reason.empty() ? "" : ", ", m.name.c_str(), law->length_scale,
                    law->fracture_energy, law->residual_stiffness,
                    law->anisotropic ? ", fourth-order anisotropic" : "");
      phase_field_reason += text;
    }
  plan.push_back(
      {"phase field", !phase_field_reason.empty(),
       phase_field_reason.empty()
           ? "no phase-field material: no nodal phase-field solve"
           : "AT2 phase field ([KT19]) on " + phase_field_reason +
                 ": nodal system solved each step by conjugate gradients, preconditioned by an "
                 "exact solve on the cracked particles' nodes, by a multigrid V-cycle once its "
                 "solves need more than 150 iterations on average (by sparse LDLT of the whole "
                 "system "
                 "in a step where they pass 300 iterations and the cost of that "
                 "factorisation), one field per body; "
                 "Hencky elasticity with the spectral tension-compression split"});
  const std::size_t bodies = problem.body_names.size();
  std::string partition_reason;
  if (problem.contact.partitioning == Partitioning::bodies)
    partition_reason =
        "partitioning = \"bodies\" in [contact]: body 0 and the other bodies are "
        "two always-separable fields (multimaterial contact, [NBS18] §2.2)";
  else if (problem.contact.partitioning == Partitioning::off)
    partition_reason = "partitioning = \"off\" in [contact]: one velocity field (single-field MPM)";
  else if (partitioning_active(problem))
    partition_reason =
        "damage-field-gradient partitioning with two fields per node (" +
        (bodies > 1 ? std::to_string(bodies) + " bodies, surface flags make them separable"
                    : std::string("damage can open cracks")) +
        "); kernel neighbour search radius = cell diagonal";
  else
    partition_reason = "one body and no damage: one velocity field, no neighbour search";
  plan.push_back({"partitioning", partitioning_active(problem), partition_reason});
  plan.push_back({"thermal", problem.thermal.active(),
                  problem.thermal.active()
                      ? problem.thermal.reason
                      : "no thermal data and no heat sources: no thermal arrays"});
  return plan;
}

template bool partitioning_active<2>(const Problem<2>&);
template bool partitioning_active<3>(const Problem<3>&);
template std::vector<ModuleDecision> plan_modules<2>(const Problem<2>&);
template std::vector<ModuleDecision> plan_modules<3>(const Problem<3>&);

}  // namespace fragmpm::mpm
