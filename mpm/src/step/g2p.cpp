// G2P ([XLS21] eq. (64)-(66)) and the constitutive update that closes the step
// (update-stress-last): velocities and positions from the grid, F and the CPDI domain by the
// midpoint increment, then stress, damage and stored energy. APIC ([JSS15]) sets the velocity to
// the grid interpolant (no FLIP increment) and keeps the affine matrix C_p = L_p, the particle's
// velocity gradient: for the linear hat this is [JSS15]'s B_p D_p⁻¹ exactly (D_p is diagonal with
// entries f(1 − f) h², and S̄ D_p⁻¹ (x_i − x_p) = ∇S̄), and for uGIMP and CPDI it is the gradient
// the deformation update already uses, exact for a rigid or affine grid motion.
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "step/affine_motion.hpp"
#include "step/constitutive_update.hpp"
#include "step/failed_domain.hpp"
#include "step/failure_text.hpp"
#include "step/particle_loops.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

namespace {

template <int D>
NumericalFailure inverted_particle(const StepState<D>& state, std::int64_t p, double dt) {
  const auto& P = state.problem.particles;
  NumericalFailure failure;
  failure.step = state.step + 1;
  failure.time = state.time + dt;
  failure.particle = p;
  failure.what = "particle " + std::to_string(p) + " (body " + std::to_string(P.body[p]) +
                 ", material '" + state.problem.materials[P.material[p]].name + "', damage " +
                 std::to_string(P.damage[p]) +
                 ") became inverted or non-finite: J = " + format_number(P.F[p].determinant()) +
                 ", F = " + format_matrix<D>(P.F[p]) + ", x = " + format_vector<D>(P.x[p]) +
                 " m, v = " + format_vector<D>(P.v[p]) + " m/s, dt = " + format_number(dt) + " s";
  return failure;
}

}  // namespace

template <int D, ShapeFunctionKind Kind, bool Partitioned, bool Thermal, bool Affine>
std::optional<NumericalFailure> grid_to_particles(StepState<D>& state, double dt) {
  auto& P = state.problem.particles;
  const NodeFields<D>& N = state.nodes;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  const double pic = state.problem.time.pic_fraction;
  constexpr bool deform_domain = Kind == ShapeFunctionKind::cpdi;
  const Vec<D> gravity = state.problem.gravity;
  const bool loaded = !state.load_force.empty();
  const bool penalty = state.penalty_walls;
  const double cell_size = state.grid.cell_size;
  double kinetic = 0.0, strain = 0.0, gravity_work = 0.0, load_work = 0.0, dissipated = 0.0,
         flowed = 0.0, penalty_work = 0.0, max_speed = 0.0, history_excess = 0.0,
         paired_overlap = 0.0;
  // Σ_p m_p a_p·Σ_i S̄_ip w_i, the particle half of the transfer's strain-side gap, w the force
  // increment of strain_side_pairing (transfer_energy.cpp); FLIP only.
  const bool strain_gap = !Affine && state.plan.books_strain_gap;
  const auto& touched = N.touched;
  std::int64_t failed = -1;
  const bool nonlocal = state.nonlocal_damage;
  if (nonlocal) size_array(state.local_equivalent, P.size());
  const int slots = omp_get_max_threads();
  constexpr int A = Axial<D>::RowsAtCompileTime;
  constexpr std::size_t per_thread = D + A;
  size_array(state.momentum_parts, per_thread * static_cast<std::size_t>(slots));
  std::fill(state.momentum_parts.begin(), state.momentum_parts.end(), 0.0);
#pragma omp parallel reduction(+ : kinetic, strain, gravity_work, load_work, dissipated, flowed, penalty_work, history_excess, paired_overlap) reduction(max : max_speed)
  {
    Stencil<D> s;
    Vec<D> momentum = Vec<D>::Zero();
    Axial<D> angular_momentum = Axial<D>::Zero();
    std::int64_t first_failed = -1;
#pragma omp for schedule(static) nowait
    for (std::int64_t p = 0; p < n; ++p) {
      fill_stencil<D, Kind>(P, p, state.grid, s);
      Vec<D> v_pic = Vec<D>::Zero(), v_change = Vec<D>::Zero(), paired_change = Vec<D>::Zero();
      Mat<D> velocity_gradient = Mat<D>::Zero();
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        const int f = field_at<D, Partitioned>(state, p, e);
        const Vec<D>& velocity = N.velocity[f][i];
        v_pic += s.weight[e] * velocity;
        if constexpr (!Affine) {
          const Vec<D> received = s.weight[e] * (velocity - N.velocity_lumped[f][i]);
          v_change += received;
          if (strain_gap) switch (strain_side_pairing(touched, i)) {
              case StrainSidePairing::own:
                paired_change += received;
                break;
              case StrainSidePairing::welded: {
                const WeldedNode<D> welded =
                    welded_node(N, state.fields(), i, state.negligible_mass);
                paired_change += (s.weight[e] * dt / welded.mass) * welded.force;
                break;
              }
              case StrainSidePairing::none:
                break;
            }
        }
        velocity_gradient += velocity * s.gradient[e].transpose();
      }
      if (strain_gap) paired_overlap += P.mass[p] * v_change.dot(paired_change);
      const Vec<D> displacement = dt * v_pic;
      P.x[p] += displacement;
      if constexpr (Affine) {
        P.v[p] = v_pic;
        P.affine[p] = velocity_gradient;
      } else {
        P.v[p] = (1.0 - pic) * (P.v[p] + v_change) + pic * v_pic;
      }
      // [XLS21] eq. (66) updates F with I + Δt L, which stretches a rigidly rotating body by (ωΔt)²
      // per step (a spinning disk builds up stress). The midpoint increment [HW80]
      // (I − ΔtL/2)⁻¹(I + ΔtL/2) agrees to O(Δt²) and is exactly orthogonal for a spin.
      const Mat<D> half_step = 0.5 * dt * velocity_gradient;
      const Mat<D> increment =
          (Mat<D>::Identity() - half_step).inverse() * (Mat<D>::Identity() + half_step);
      P.F[p] = increment * P.F[p];
      if constexpr (deform_domain) P.domain[p] = increment * P.domain[p];
      const double J = P.F[p].determinant();
      if (!(J > 0.0) || !P.v[p].allFinite() || !P.F[p].allFinite()) {
        if (first_failed < 0) first_failed = p;
        continue;
      }
      if (nonlocal && state.material_nonlocal[static_cast<std::size_t>(P.material[p])]) {
        // The damage law needs the neighbours' σ₁ of this step: stress, damage and stored energy
        // follow in nonlocal_constitutive_update once every particle has its trial stress.
        double psi;
        state.local_equivalent[static_cast<std::size_t>(p)] =
            largest_principal_stress<D>(trial_stress<D, Thermal>(state, p, psi));
      } else {
        const ConstitutiveResult energy = update_constitutive<D, Thermal, true>(state, p, dt);
        strain += P.volume0[p] * energy.stored;
        dissipated += P.volume0[p] * energy.dissipated;
        flowed += P.volume0[p] * energy.flowed;
        history_excess += P.volume0[p] * energy.history_excess;
        if constexpr (deform_domain)
          if (P.damage[p] >= 1.0)
            settle_failed_domain<D>(
                P.domain[p], P.volume0[p] * J,
                state.material_failed_fluid[static_cast<std::size_t>(P.material[p])], cell_size);
      }
      kinetic += 0.5 * P.mass[p] * P.v[p].squaredNorm();
      angular_momentum += P.mass[p] * cross<D>(P.x[p], P.v[p]);
      if constexpr (Affine) {
        const Mat<D> moment = domain_second_moment<D>(P, static_cast<std::size_t>(p), Kind);
        kinetic += affine_kinetic_energy<D>(P.mass[p], P.affine[p], moment);
        angular_momentum += P.mass[p] * axial<D>(P.affine[p] * moment);
      }
      gravity_work += P.mass[p] * gravity.dot(displacement);
      if (loaded) load_work += state.load_force[p].dot(displacement);
      if (penalty) penalty_work += state.penalty_force[p].dot(displacement);
      momentum += P.mass[p] * P.v[p];
      const std::size_t material = static_cast<std::size_t>(P.material[p]);
      const double wave_speed = particle_wave_speed<D>(
          state.models[material], state.elastic_laws[material],
          state.problem.materials[material].degradation, P, static_cast<std::size_t>(p));
      max_speed = std::max(max_speed, wave_speed + P.v[p].norm());
    }
    const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
    for (int k = 0; k < D; ++k) state.momentum_parts[t * per_thread + k] = momentum[k];
    for (int k = 0; k < A; ++k) state.momentum_parts[t * per_thread + D + k] = angular_momentum[k];
#pragma omp critical(fragmpm_g2p_failure)
    if (first_failed >= 0 && (failed < 0 || first_failed < failed)) failed = first_failed;
  }
  if (failed >= 0) return inverted_particle(state, failed, dt);
  if (nonlocal) {
    const ConstitutiveSums sums =
        nonlocal_constitutive_update<D, Thermal>(state, dt, deform_domain);
    strain += sums.stored;
    dissipated += sums.dissipated;
    flowed += sums.flowed;
  }
  state.row.momentum.setZero();
  state.row.angular_momentum.setZero();
  for (std::size_t t = 0; t < static_cast<std::size_t>(slots); ++t) {
    for (int k = 0; k < D; ++k) state.row.momentum[k] += state.momentum_parts[t * per_thread + k];
    for (int k = 0; k < A; ++k)
      state.row.angular_momentum[k] += state.momentum_parts[t * per_thread + D + k];
  }
  state.strain_gap.particles = 0.5 * paired_overlap;
  state.row.kinetic = kinetic;
  state.row.strain = strain;
  state.totals.gravity_work += gravity_work;
  state.totals.load_work += load_work;
  state.totals.wall_work += penalty_work;  // penalty walls (penalty_walls.cpp)
  state.totals.dissipated += dissipated;
  state.totals.flow_dissipation += flowed;
  state.totals.history_excess += history_excess;
  state.next_dt_limit =
      max_speed > 0.0 ? state.problem.time.cfl * cell_size / (std::sqrt(double(D)) * max_speed)
                      : std::numeric_limits<double>::infinity();
  return std::nullopt;
}

#define FRAGMPM_INSTANTIATE_ONE(D, K, PARTITIONED, THERMAL, AFFINE) \
  template std::optional<NumericalFailure>                          \
  grid_to_particles<D, ShapeFunctionKind::K, PARTITIONED, THERMAL, AFFINE>(StepState<D>&, double);
#define FRAGMPM_INSTANTIATE_KIND(D, K)               \
  FRAGMPM_INSTANTIATE_ONE(D, K, false, false, false) \
  FRAGMPM_INSTANTIATE_ONE(D, K, false, true, false)  \
  FRAGMPM_INSTANTIATE_ONE(D, K, true, false, false)  \
  FRAGMPM_INSTANTIATE_ONE(D, K, true, true, false)   \
  FRAGMPM_INSTANTIATE_ONE(D, K, false, false, true)  \
  FRAGMPM_INSTANTIATE_ONE(D, K, false, true, true)   \
  FRAGMPM_INSTANTIATE_ONE(D, K, true, false, true)   \
  FRAGMPM_INSTANTIATE_ONE(D, K, true, true, true)
#define FRAGMPM_INSTANTIATE(D)        \
  FRAGMPM_INSTANTIATE_KIND(D, linear) \
  FRAGMPM_INSTANTIATE_KIND(D, ugimp)  \
  FRAGMPM_INSTANTIATE_KIND(D, cpdi)   \
  FRAGMPM_INSTANTIATE_KIND(D, bspline2)
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE
#undef FRAGMPM_INSTANTIATE_KIND
#undef FRAGMPM_INSTANTIATE_ONE

}  // namespace fragmpm::mpm
