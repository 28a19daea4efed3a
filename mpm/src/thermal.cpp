// Per-particle thermal quantities that the solver and the scene checks share.
#include "fragmpm/mpm/thermal.hpp"

#include <algorithm>
#include <limits>

namespace fragmpm::mpm {

template <int D>
double thermal_stable_time_step(const Problem<D>& problem, const Particles<D>& particles,
                                double courant) {
  const auto& materials = problem.thermal.materials;
  double limit = std::numeric_limits<double>::infinity();
  if (materials.empty() || particles.temperature.empty()) return limit;
  const double h = problem.grid.cell_size;
  const std::int64_t n = static_cast<std::int64_t>(particles.size());
#pragma omp parallel for reduction(min : limit) schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const ThermalMaterial& m = materials[static_cast<std::size_t>(particles.material[p])];
    if (!(m.conductivity > 0.0)) continue;
    const double density =
        particles.mass[p] / (particles.volume0[p] * particles.F[p].determinant());
    limit =
        std::min(limit, courant * density * m.specific_heat * h * h / (2.0 * D * m.conductivity));
  }
  return limit;
}

template <int D>
double thermal_energy(const Problem<D>& problem, const Particles<D>& particles) {
  const auto& materials = problem.thermal.materials;
  if (materials.empty() || particles.temperature.empty()) return 0.0;
  double sum = 0.0;
  for (std::size_t p = 0; p < particles.size(); ++p) {
    const ThermalMaterial& m = materials[static_cast<std::size_t>(particles.material[p])];
    sum +=
        particles.mass[p] * m.specific_heat * (particles.temperature[p] - m.reference_temperature);
  }
  return sum;
}

template double thermal_stable_time_step<2>(const Problem<2>&, const Particles<2>&, double);
template double thermal_stable_time_step<3>(const Problem<3>&, const Particles<3>&, double);
template double thermal_energy<2>(const Problem<2>&, const Particles<2>&);
template double thermal_energy<3>(const Problem<3>&, const Particles<3>&);

}  // namespace fragmpm::mpm
