// Particles that leave the computational domain under `[grid] outside = "remove"`: found after the
// step, booked as lost and removed from every per-particle array before the next step begins.
//
// Energy. The balance of a step reads kinetic + strain + (dissipated, friction, contact) − (initial
// + external work) = error. Removing particle p takes K_p = ½ m_p |v_p|² (plus ½ m tr(C Q Cᵀ) with
// APIC) out of `kinetic` and its stored energy V₀ ψ_p(F, d) out of `strain`. Both are booked
// (`lost.kinetic`, `lost.strain`) and added to the left-hand side, so the error of the step is the
// same as if p had stayed and flown on: a particle in free flight keeps its K_p and ψ_p, since no
// node it maps to carries other mass. The stored energy is the constitutive update's own value for
// the particle's F and d, the same number G2P added to `strain` this step. Heat content Σ m c θ is
// not part of the balance and simply leaves with the particle.
//
// Determinism. The search is a parallel OR; the removal list, the booked sums and the compaction
// run in particle order on one thread, so the result does not depend on the thread count.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "fragmpm/mpm/solver.hpp"
#include "step/affine_motion.hpp"
#include "step/constitutive_update.hpp"
#include "step/failure_text.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

namespace {

template <int D>
bool outside_domain(const Vec<D>& x, const GridSpec<D>& grid) {
  return !x.allFinite() || (x - grid.min).minCoeff() < 0.0 || (grid.max - x).minCoeff() < 0.0;
}

/// A departure that is a numerical failure: a non-finite state, or a speed no fragment can reach.
template <int D>
std::optional<NumericalFailure> check_departure(const StepState<D>& state, std::size_t p,
                                                double dt) {
  const auto& P = state.problem.particles;
  const double speed = P.v[p].norm();
  std::string why;
  if (!P.x[p].allFinite() || !P.v[p].allFinite())
    why = "a non-finite position or velocity";
  else if (speed > state.departure_speed_limit)
    why = "a speed of " + std::to_string(speed) + " m/s, more than " +
          std::to_string(static_cast<int>(departure_speed_factor)) +
          " times the largest wave speed of the scene's materials (" +
          std::to_string(state.departure_speed_limit / departure_speed_factor) +
          " m/s): no fragment is thrown that fast, the step is unstable";
  else
    return std::nullopt;
  NumericalFailure failure;
  failure.step = state.step + 1;
  failure.time = state.time + dt;
  failure.particle = static_cast<long long>(p);
  failure.what = "particle " + std::to_string(p) + " (body " + std::to_string(P.body[p]) +
                 ") left the computational domain with " + why +
                 "; x = " + format_vector<D>(P.x[p]) + " m, v = " + format_vector<D>(P.v[p]) +
                 " m/s, domain " + format_vector<D>(state.problem.grid.min) + " to " +
                 format_vector<D>(state.problem.grid.max) + " m";
  return failure;
}

/// Kinetic energy, including the affine part the APIC transfer carries (as G2P books it) [J].
template <int D>
double particle_kinetic_energy(const StepState<D>& state, std::size_t p) {
  const auto& P = state.problem.particles;
  double kinetic = 0.5 * P.mass[p] * P.v[p].squaredNorm();
  if (state.problem.time.transfer == Transfer::apic)
    kinetic += affine_kinetic_energy<D>(
        P.mass[p], P.affine[p], domain_second_moment<D>(P, p, state.problem.grid.shape_function));
  return kinetic;
}

/// Angular momentum about the origin, as G2P books it.
template <int D>
Axial<D> particle_angular_momentum(const StepState<D>& state, std::size_t p) {
  const auto& P = state.problem.particles;
  Axial<D> spin = P.mass[p] * cross<D>(P.x[p], P.v[p]);
  if (state.problem.time.transfer == Transfer::apic)
    spin += P.mass[p] * axial<D>(P.affine[p] *
                                 domain_second_moment<D>(P, p, state.problem.grid.shape_function));
  return spin;
}

}  // namespace

template <int D>
void remap_particle_references(Problem<D>& problem, const std::vector<std::int64_t>& new_index) {
  auto remap = [&new_index](std::vector<std::int64_t>& particles, std::vector<double>& measure) {
    std::size_t to = 0;
    for (std::size_t k = 0; k < particles.size(); ++k) {
      const std::int64_t p = new_index[static_cast<std::size_t>(particles[k])];
      if (p < 0) continue;
      particles[to] = p;
      measure[to] = measure[k];
      ++to;
    }
    particles.resize(to);
    measure.resize(to);
  };
  for (TractionLoad<D>& load : problem.loads) remap(load.particles, load.boundary_measure);
  for (HeatFluxLoad& load : problem.thermal.edge_loads)
    remap(load.particles, load.boundary_measure);
}

template <int D>
std::optional<NumericalFailure> remove_departed_particles(StepState<D>& state, double dt) {
  auto& P = state.problem.particles;
  const GridSpec<D>& grid = state.problem.grid;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  bool any = false;
#pragma omp parallel for reduction(|| : any) schedule(static)
  for (std::int64_t p = 0; p < n; ++p) any = any || outside_domain<D>(P.x[p], grid);
  if (!any) return std::nullopt;

  std::vector<std::size_t> removed;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (outside_domain<D>(P.x[p], grid)) {
      if (auto failure = check_departure(state, p, dt)) return failure;
      removed.push_back(p);
    }

  LostParticles& lost = state.totals.lost;
  SeriesRow<D>& row = state.row;
  for (const std::size_t p : removed) {
    const double kinetic = particle_kinetic_energy(state, p);
    // ψ of the current F and d: update_constitutive without damage growth rewrites the stress it
    // wrote in G2P with the same value and returns the stored energy G2P added to `strain`.
    const double stored =
        P.volume0[p] * (state.thermal ? update_constitutive<D, true, false>(state, p, 0.0).stored
                                      : update_constitutive<D, false, false>(state, p, 0.0).stored);
    const Vec<D> momentum = P.mass[p] * P.v[p];
    ++lost.count;
    lost.mass += P.mass[p];
    lost.kinetic += kinetic;
    lost.strain += stored;
    for (int k = 0; k < D; ++k) lost.momentum[static_cast<std::size_t>(k)] += momentum[k];
    row.kinetic -= kinetic;
    row.strain -= stored;
    row.momentum -= momentum;
    row.angular_momentum -= particle_angular_momentum(state, p);
  }

  std::vector<std::int64_t> new_index(P.size());
  for (std::size_t p = 0, next = 0, kept = 0; p < P.size(); ++p) {
    if (next < removed.size() && removed[next] == p) {
      new_index[p] = -1;
      ++next;
    } else {
      new_index[p] = static_cast<std::int64_t>(kept++);
    }
  }
  P.erase(removed);
  erase_entries(state.degradable, removed);
  erase_entries(state.release_before, removed);
  erase_entries(state.flow_heat, removed);
  remap_particle_references(state.problem, new_index);
  if (!state.load_force.empty()) state.load_force.resize(P.size());
  if (state.thermal) state.thermal->remove_particles(P, removed);
  // The CFL limit of the particles that remain, as a restart from this state computes it.
  state.next_dt_limit = stable_time_step<D>(state.problem, P, state.problem.time.cfl);
  return std::nullopt;
}

#define FRAGMPM_INSTANTIATE(D)                                                               \
  template void remap_particle_references<D>(Problem<D>&, const std::vector<std::int64_t>&); \
  template std::optional<NumericalFailure> remove_departed_particles<D>(StepState<D>&, double);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
