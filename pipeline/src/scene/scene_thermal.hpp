#pragma once
// Private to the scene compiler: thermal keys of materials, bodies and walls, and the decision
// whether the thermal module runs (docs/design.md "Leave out what a scene does not need").
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fragmpm/mpm/problem.hpp"
#include "scene_toml.hpp"

namespace fragmpm::pipeline::scene_detail {

/// Keys a [[materials]] entry may carry for the thermal module.
const std::vector<std::string_view>& thermal_material_keys();

/// The `temperature` key of a [[bodies]] entry (initial temperature of its particles) [K].
std::optional<double> read_body_temperature(const Section& body);

/// The `thermal = { … }` table of a [[walls]] entry, for wall index `wall`.
std::optional<mpm::ThermalWallCondition<2>> read_wall_thermal(const Section& wall_section,
                                                              const mpm::WallSpec<2>& wall);

/// `conductance`, `conductance_pressure`, `conductance_exponent` of [contact] ([XLS21] eq.
/// (12)-(13)).
void read_contact_conductance(const Section& contact, mpm::ThermalSpec<2>& thermal);

/// Decides whether the thermal module runs and, if so, fills problem.thermal.materials (reason
/// included) and the particles' initial temperatures: body temperature, else the material's
/// `temperature`, else 20 °C. The module runs when any material has a thermal key, any body a
/// temperature, any wall a thermal condition, or a [[loads]] entry puts heat in (already in
/// problem.thermal.edge_loads); then every material needs `heat_capacity`.
/// `body_temperature[b]` is per body id; `wall_conditions` were read by read_wall_thermal.
void compile_thermal(mpm::Problem<2>& problem, const std::vector<Section>& material_sections,
                     const std::vector<std::optional<double>>& body_temperature,
                     const std::vector<mpm::ThermalWallCondition<2>>& wall_conditions);

}  // namespace fragmpm::pipeline::scene_detail
