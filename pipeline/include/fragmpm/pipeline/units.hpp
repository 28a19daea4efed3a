#pragma once
// Physical quantities written with their unit ("50 GPa", "2.3 g/cm3", "800 C"), converted once at
// input to SI (docs/design.md). A bare number is already SI.
//
// Unit expressions: symbols with an optional SI prefix (p n u µ μ m c d k M G T) and an optional
// integer exponent ("cm3", "m^3", "s^-1", "m²"), multiplied by a space, '*' or '·' and divided by
// '/'. After a '/' only one factor or a parenthesised group is the denominator, so "J/(kg K)" is
// accepted and the ambiguous "J/kg K" is refused.
// Symbols: m, g, s, K, Pa, N, J, W, Hz, rad, deg, bar, C / °C / degC (Celsius: only on its own,
// since it is an affine scale: θ[K] = θ[°C] + 273.15).
#include <stdexcept>
#include <string>
#include <string_view>

namespace fragmpm::pipeline {

/// What a scene value measures; decides which units are accepted and the SI unit of the result.
enum class QuantityKind {
  length,            ///< m
  time,              ///< s
  mass,              ///< kg
  density,           ///< kg/m3
  pressure,          ///< Pa (stress, elastic modulus)
  velocity,          ///< m/s
  acceleration,      ///< m/s2
  frequency,         ///< Hz
  angle,             ///< rad
  angular_velocity,  ///< rad/s
  temperature,       ///< K
  energy_per_area,   ///< J/m2 (fracture energy)
  specific_heat,     ///< J/(kg K)
  conductivity,      ///< W/(m K)
  expansion,         ///< 1/K
  area,              ///< m2 (total grain area of a stacked column)
  volume,            ///< m3 (Weibull reference volume)
  inverse_velocity,  ///< s/m (slope of velocity-dependent friction)
  heat_flux,         ///< W/m2 (thermal boundary flux)
  film_coefficient,  ///< W/(m2 K) (convection, contact conductance)
  stiffness,         ///< Pa/m (penalty stiffness of a wall, [XLS21] eq. (83))
};

/// The quantity string could not be read or has the wrong kind of unit. The message says what was
/// expected (kind and SI unit) and what was found; the scene parser adds file, line and key.
struct UnitError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// "pressure", "length", ... (for messages).
std::string_view kind_name(QuantityKind kind);
/// The SI unit of a kind as written in scene files: "Pa", "m", "kg/m3", ...
std::string_view si_unit(QuantityKind kind);

/// Parses "<number> [unit]" and returns the value in the SI unit of `kind`. Without a unit the
/// number is taken as SI. Throws UnitError on an unreadable number, an unknown unit symbol, or a
/// unit of another kind (e.g. "5 m" for a pressure).
double parse_quantity(std::string_view text, QuantityKind kind);

}  // namespace fragmpm::pipeline
