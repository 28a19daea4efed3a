#pragma once
// Private to the scene compiler: the fracture and contact keys of a scene — damage laws
// and strengths of [[materials]], friction laws (shared by [contact] and [[walls]]), the [contact]
// table and [[loads]] tractions. Format: scenes/README.md.
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fragmpm/mpm/problem.hpp"
#include "scene_toml.hpp"

namespace fragmpm::pipeline::scene_detail {

/// The [[materials]] keys of the damage law, for allow_only.
const std::vector<std::string_view>& damage_keys();

/// Reads damage, strength, fracture_energy, crack_speed, degradation and weibull of one material
/// into `spec` (whose elastic constants are already set). `thickness` is [physics] thickness [m]
/// (needed for Weibull volumes in 2D). For Rankine softening, refuses a material whose
/// characteristic length makes H̄ l_ch ≥ 1 (snap-back, [XLS21] eq. (20)-(21)), naming the largest
/// admissible cell size (or l_ch when the scene gives one); l_ch is mpm::characteristic_length, the
/// solver's: the given characteristic_length or the particle size s = `particle_spacing` = h/n.
/// A Weibull material's median strength is checked at the particle volume s² × thickness.
void read_damage(const Section& material, mpm::MaterialSpec& spec, std::optional<double> thickness,
                 const mpm::GridSpec<2>& grid, double particle_spacing);

/// Fills Particles::strength: +inf for materials without damage, σ_f for a uniform strength, and a
/// Weibull draw ([HH17] eq. (25)) per particle otherwise, one seeded stream per material over its
/// particles in particle order. Warns on stderr with the number of drawn Rankine strengths that
/// snap back at the particle's l_ch (mpm::characteristic_length, as in the solver).
void assign_strengths(mpm::Problem<2>& problem, const std::vector<Section>& material_sections);

/// A friction law written as a number (Coulomb μ) or a table { law = "...", ... } under key k of s.
mpm::FrictionLaw read_friction(const Section& s, std::string_view k);

/// The [contact] table.
mpm::ContactSpec<2> read_contact(const Section& contact);

/// One [[loads]] entry. `bodies` maps a body name — or the name of an image/grain entry, meaning
/// all its grains — to body ids. Selects the loaded particles in problem.particles.
mpm::TractionLoad<2> read_load(const Section& load, std::size_t index,
                               const mpm::Problem<2>& problem,
                               const std::map<std::string, std::vector<std::int32_t>>& bodies);

/// True when a [[loads]] entry is a heat input (heat_flux, or film_coefficient with ambient) rather
/// than a traction.
bool is_heat_load(const Section& load);

/// A heat-input [[loads]] entry (same particle selection as a traction; [XLS21] eq. (44), (57)).
mpm::HeatFluxLoad read_heat_load(const Section& load, std::size_t index,
                                 const mpm::Problem<2>& problem,
                                 const std::map<std::string, std::vector<std::int32_t>>& bodies);

}  // namespace fragmpm::pipeline::scene_detail
