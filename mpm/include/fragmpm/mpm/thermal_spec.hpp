#pragma once
// Scene data of the thermal module (docs/design.md "Thermal module"; [XLS21] §2.1-2.3, §3.1):
// per-material thermal constants and thermal boundary conditions. Empty `materials` = the module is
// off: no thermal arrays and no thermal loop (docs/design.md "Leave out what a scene does not
// need").
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "fragmpm/mpm/types.hpp"
#include "fragmpm/mpm/velocity_history.hpp"
#include "fragmpm/mpm/wall_region.hpp"

namespace fragmpm::mpm {

/// Thermal constants of one material (index = material index of the problem).
struct ThermalMaterial {
  double conductivity = 0.0;   ///< κ [W/(m K)] of q = −κ ∇θ ([XLS21] eq. (18))
  double specific_heat = 0.0;  ///< c [J/(kg K)] ([XLS21] eq. (4), (38))
  double expansion = 0.0;      ///< α_t [1/K] ([XLS21] eq. (3))
  double reference_temperature =
      0.0;  ///< θ₀ [K] of the coupling energy M ([XLS21] eq. (3)); zero thermal stress at θ₀
};

/// A thermal condition on the material next to a plane ([XLS21] eq. (44), (57)): a rigid wall's
/// plane, or a plane that only carries the condition (scene kind = "thermal", no mechanical
/// action).
enum class ThermalWallKind {
  insulated,    ///< q·n = 0 (the natural condition; the default)
  temperature,  ///< θ = θ̄ at the wall nodes (Γ_θ)
  flux,         ///< heat flux q̄ into the material [W/m²] (Γ_q)
  convection,   ///< q into the material = h (θ_∞ − θ) [W/m²] (Γ_h)
};

template <int D>
struct ThermalWallCondition {
  std::string name;
  Vec<D> point = Vec<D>::Zero();   ///< a point of the plane at t = 0 [m]
  Vec<D> normal = Vec<D>::Zero();  ///< unit, into the material
  VelocityHistory<D> velocity;     ///< the plane moves with its wall
  WallRegion<D> region;            ///< the part of the plane that acts, as for its wall
  ThermalWallKind kind = ThermalWallKind::insulated;
  double temperature = 0.0;       ///< θ̄ (temperature) or θ_∞ (convection) [K]
  double flux = 0.0;              ///< q̄ into the material [W/m²] (flux)
  double film_coefficient = 0.0;  ///< h [W/(m² K)] (convection)
};

/// A heat flux into the material through part of a body's boundary, carried by particles like a
/// traction load: Q_p = q̄ a_p with a_p the boundary length (2D) the particle carries ([XLS21] eq.
/// (57)).
struct HeatFluxLoad {
  std::string name;
  std::vector<std::int64_t> particles;
  std::vector<double> boundary_measure;          ///< a_p [m in 2D, m² in 3D]
  ThermalWallKind kind = ThermalWallKind::flux;  ///< flux or convection
  double flux = 0.0;                             ///< q̄ [W/m²]
  double temperature = 0.0;                      ///< θ_∞ [K] (convection)
  double film_coefficient = 0.0;                 ///< h [W/(m² K)] (convection)
};

template <int D>
struct ThermalSpec {
  std::vector<ThermalMaterial> materials;  ///< one per problem material; empty = module off
  std::vector<ThermalWallCondition<D>> walls;
  std::vector<HeatFluxLoad> edge_loads;
  /// Contact conductance h_c = h₀ |p/p₀|^ε at separable nodes in contact ([XLS21] eq. (12); ε = 1
  /// is eq. (13) with γ̄ = h₀/p₀). h₀ = 0: contacts pass no heat by conduction (friction heat still
  /// flows).
  double contact_conductance = 0.0;  ///< h₀ [W/(m² K)]
  double contact_pressure = 1.0;     ///< p₀ [Pa]
  double contact_exponent = 1.0;     ///< ε
  /// Why the scene needs the module (logged in /meta), e.g. "material 'rock' has thermal data".
  std::string reason;

  bool active() const { return !materials.empty(); }
};

}  // namespace fragmpm::mpm
