// Thermal scene keys (scenes/README.md "Thermal module"): materials, body temperatures, walls.
#include "scene_thermal.hpp"

#include <cmath>

namespace fragmpm::pipeline::scene_detail {
namespace {

using QK = QuantityKind;

/// Room temperature, the initial temperature when a thermal scene gives none [K].
constexpr double kDefaultTemperature = 293.15;

double absolute_temperature(const Section& s, std::string_view key) {
  const double t = s.quantity(key, QK::temperature);
  if (!(t > 0.0)) s.expected(key, "an absolute temperature above 0 K");
  return t;
}

}  // namespace

const std::vector<std::string_view>& thermal_material_keys() {
  static const std::vector<std::string_view> keys = {"conductivity", "heat_capacity", "expansion",
                                                     "temperature", "reference_temperature"};
  return keys;
}

std::optional<double> read_body_temperature(const Section& body) {
  if (!body.has("temperature")) return std::nullopt;
  return absolute_temperature(body, "temperature");
}

std::optional<mpm::ThermalWallCondition<2>> read_wall_thermal(const Section& w,
                                                              const mpm::WallSpec<2>& wall) {
  const std::optional<Section> t = w.optional_table("thermal");
  if (!t) return std::nullopt;
  t->allow_only({"temperature", "flux", "film_coefficient", "ambient"});
  mpm::ThermalWallCondition<2> c;
  c.name = wall.name;
  c.point = wall.point;
  c.normal = wall.normal;
  c.velocity = wall.velocity;
  c.region = wall.region;
  const int given =
      int(t->has("temperature")) + int(t->has("flux")) + int(t->has("film_coefficient"));
  if (given != 1)
    t->fail_table(
        "expected exactly one of temperature (fixed temperature), flux (heat flux into the "
        "material) or "
        "film_coefficient with ambient (convection), got " +
        std::to_string(given));
  if (t->has("temperature")) {
    if (t->has("ambient"))
      t->fail("ambient", "expected ambient only with film_coefficient (convection)");
    c.kind = mpm::ThermalWallKind::temperature;
    c.temperature = absolute_temperature(*t, "temperature");
  } else if (t->has("flux")) {
    if (t->has("ambient"))
      t->fail("ambient", "expected ambient only with film_coefficient (convection)");
    c.kind = mpm::ThermalWallKind::flux;
    c.flux = t->quantity("flux", QK::heat_flux);
  } else {
    c.kind = mpm::ThermalWallKind::convection;
    c.film_coefficient = t->quantity("film_coefficient", QK::film_coefficient);
    if (!(c.film_coefficient >= 0.0))
      t->expected("film_coefficient", "a heat transfer coefficient >= 0");
    if (!t->has("ambient"))
      t->fail("ambient", "missing required key: convection needs the ambient temperature");
    c.temperature = absolute_temperature(*t, "ambient");
  }
  return c;
}

void read_contact_conductance(const Section& c, mpm::ThermalSpec<2>& thermal) {
  if (!c.has("conductance")) {
    for (std::string_view k : {"conductance_pressure", "conductance_exponent"})
      if (c.has(k)) c.fail(k, "expected " + std::string(k) + " only together with conductance");
    return;
  }
  thermal.contact_conductance = c.quantity("conductance", QK::film_coefficient);
  if (!(thermal.contact_conductance >= 0.0))
    c.expected("conductance", "a contact conductance h0 >= 0");
  thermal.contact_pressure =
      c.optional_quantity("conductance_pressure", QK::pressure).value_or(1.0);
  if (!(thermal.contact_pressure > 0.0))
    c.expected("conductance_pressure", "a positive reference pressure p0");
  thermal.contact_exponent = c.optional_number("conductance_exponent").value_or(1.0);
  if (!(thermal.contact_exponent > 0.0))
    c.expected("conductance_exponent", "a positive exponent epsilon");
}

void compile_thermal(mpm::Problem<2>& problem, const std::vector<Section>& material_sections,
                     const std::vector<std::optional<double>>& body_temperature,
                     const std::vector<mpm::ThermalWallCondition<2>>& wall_conditions) {
  std::string reason;
  for (std::size_t m = 0; m < material_sections.size() && reason.empty(); ++m)
    for (std::string_view k : thermal_material_keys())
      if (material_sections[m].has(k)) {
        reason = "material '" + problem.materials[m].name + "' has thermal data (" +
                 std::string(k) + ")";
        break;
      }
  for (std::size_t b = 0; b < body_temperature.size() && reason.empty(); ++b)
    if (body_temperature[b]) reason = "body '" + problem.body_names[b] + "' sets a temperature";
  if (reason.empty() && !problem.thermal.edge_loads.empty())
    reason = "load '" + problem.thermal.edge_loads.front().name + "' puts heat into a body";
  if (reason.empty() && !wall_conditions.empty())
    reason = "wall '" + wall_conditions.front().name + "' has a thermal condition";
  if (reason.empty()) return;  // module off: no thermal arrays (docs/design.md)

  problem.thermal.reason = reason;
  std::vector<double> initial(material_sections.size(), kDefaultTemperature);
  for (std::size_t m = 0; m < material_sections.size(); ++m) {
    const Section& s = material_sections[m];
    mpm::ThermalMaterial t;
    if (!s.has("heat_capacity"))
      s.fail("heat_capacity",
             "missing required key: the thermal module runs because " + reason +
                 ", so every material needs heat_capacity (specific heat, e.g. \"800 J/(kg K)\")");
    t.specific_heat = s.quantity("heat_capacity", QK::specific_heat);
    if (!(t.specific_heat > 0.0)) s.expected("heat_capacity", "a positive specific heat");
    t.conductivity = s.optional_quantity("conductivity", QK::conductivity).value_or(0.0);
    if (!(t.conductivity >= 0.0)) s.expected("conductivity", "a thermal conductivity >= 0");
    t.expansion = s.optional_quantity("expansion", QK::expansion).value_or(0.0);
    if (!(std::abs(t.expansion) < 1e-2))
      s.expected("expansion", "a linear thermal expansion coefficient of magnitude below 1e-2 1/K");
    if (s.has("temperature")) initial[m] = absolute_temperature(s, "temperature");
    t.reference_temperature = s.has("reference_temperature")
                                  ? absolute_temperature(s, "reference_temperature")
                                  : initial[m];
    problem.thermal.materials.push_back(t);
  }
  auto& P = problem.particles;
  P.temperature.resize(P.size());
  for (std::size_t p = 0; p < P.size(); ++p) {
    const auto& body = body_temperature[static_cast<std::size_t>(P.body[p])];
    P.temperature[p] = body ? *body : initial[static_cast<std::size_t>(P.material[p])];
  }
  problem.thermal.walls = wall_conditions;
}

}  // namespace fragmpm::pipeline::scene_detail
