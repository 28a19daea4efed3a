#pragma once
// Arrays of the thermal stage (thermal_stage.cpp): per-material constants, per-particle booking
// state and per-node, per-field capacities, temperatures and heat loads. Exists only in scenes
// that need the thermal module.
#include <array>
#include <cstddef>
#include <limits>
#include <vector>

#include "fragmpm/mpm/damage_law.hpp"
#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/mpm/thermal.hpp"

namespace fragmpm::mpm {

template <int D>
struct ThermalState {
  struct FixedNode {
    std::size_t node;
    int field;
    double value;
  };

  explicit ThermalState(const Problem<D>& problem);

  /// Drops the per-particle entries of the particles at `removed` (ascending), which have just
  /// been erased from `particles`, and takes the negligible capacity from the particles that
  /// remain, as a restart from this state does.
  void remove_particles(const Particles<D>& particles, const std::vector<std::size_t>& removed);
  /// Nodes whose heat capacity is below 1e-10 of the lightest particle's m c carry no temperature.
  void set_negligible_capacity(const Particles<D>& particles);

  /// Thermal part of the trial Cauchy stress of a particle ([XLS21] eq. (3)) [Pa].
  Mat<D> stress(int material, const Mat<D>& F, double temperature) const {
    const std::size_t m = static_cast<std::size_t>(material);
    return thermal_cauchy_stress<D>(bulk[m], expansion[m], temperature, reference[m],
                                    F.determinant());
  }
  /// Interface temperature max(θ₀ᵢ, θ₁ᵢ) of a two-field node for the friction law
  /// ([XLS21] eq. (15)) [K].
  double interface_temperature(std::size_t i) const {
    return std::max(temperature[0][i], temperature[1][i]);
  }

  std::vector<double> bulk, expansion, reference, conductivity, specific_heat;
  std::vector<Degradation> degradation;
  std::vector<char> damages;
  std::vector<double> last_J, last_damage;  ///< J and d when the sources were last booked
  std::vector<double> edge_source;
  std::array<std::vector<double>, 2> capacity, heat, load, temperature, rate, wall_heat;
  std::array<std::vector<Vec<D>>, 2> domain_gradient;
  std::vector<FixedNode> fixed_nodes;
  std::vector<char> merged;       ///< per node: a thermally perfect contact this step
  bool boundary_measure = false;  ///< a flux or convection wall needs the face measure
  bool wall_friction = false;     ///< a contact wall may do friction work
  double negligible_capacity = 0.0;
  double dt_limit = std::numeric_limits<double>::infinity();  ///< conduction limit [s]
};

}  // namespace fragmpm::mpm
