// The explicit step's stability limit from the particles' current state: the CFL limit of the
// elastic waves and, with the thermal module, the explicit conduction limit.
#include <algorithm>
#include <cmath>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/mpm/thermal.hpp"
#include "fragmpm/mpm/wave_speed.hpp"

namespace fragmpm::mpm {

template <int D>
double stable_time_step(const Problem<D>& problem, const Particles<D>& particles, double cfl) {
  std::vector<NeoHookean> models;
  std::vector<ElasticLaw> laws;
  for (const auto& m : problem.materials) {
    models.push_back({m.bulk_modulus, m.shear_modulus});
    laws.push_back(elastic_law(m));
  }
  double max_speed = 0.0;
  const std::int64_t n = static_cast<std::int64_t>(particles.size());
#pragma omp parallel for reduction(max : max_speed) schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const std::size_t material = static_cast<std::size_t>(particles.material[p]);
    const double c = particle_wave_speed<D>(models[material], laws[material],
                                            problem.materials[material].degradation, particles,
                                            static_cast<std::size_t>(p));
    max_speed = std::max(max_speed, c + particles.v[p].norm());
  }
  // The explicit conduction limit joins the CFL limit when the thermal module runs
  // (docs/design.md).
  const double thermal_limit = thermal_stable_time_step<D>(problem, particles, cfl);
  if (max_speed <= 0.0) return thermal_limit;
  // Multilinear hats with a lumped mass: the stiffest grid mode of a cell has ω = 2c√D/h, so
  // central-difference stepping is stable for Δt < 2/ω = h/(c√D). The 1D textbook h/c is the 1D
  // value and lets a 2D scene run unstably at C_cfl close to 1.
  return std::min(thermal_limit, cfl * problem.grid.cell_size / (std::sqrt(double(D)) * max_speed));
}

template double stable_time_step<2>(const Problem<2>&, const Particles<2>&, double);
template double stable_time_step<3>(const Problem<3>&, const Particles<3>&, double);

}  // namespace fragmpm::mpm
