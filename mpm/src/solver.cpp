// The explicit MPM step as a sequence of stages (step/stages.hpp) over one StepState: P2G, grid
// update, contact, rigid walls, thermal, G2P with FLIP/PIC blend, update-stress-last.
#include "fragmpm/mpm/solver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include "fragmpm/mpm/thermal.hpp"
#include "fragmpm/mpm/wave_speed.hpp"
#include "step/affine_motion.hpp"
#include "step/constitutive_update.hpp"
#include "step/failure_text.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

namespace {

/// Nodes lighter than this fraction of the lightest particle carry no velocity: their mass comes
/// from the far tail of a shape function, and dividing by it would amplify round-off.
constexpr double negligible_node_mass_fraction = 1e-10;

}  // namespace

namespace {
/// FLIP carries no affine field: whatever a scene set (the velocity gradient of a spin) would
/// otherwise count in the kinetic energy and angular momentum of a run that never transfers it.
template <int D>
void settle_affine(Problem<D>& problem) {
  auto& P = problem.particles;
  if (P.affine.size() != P.size() || problem.time.transfer == Transfer::flip)
    P.affine.assign(P.size(), Mat<D>::Zero());
}

/// F_p⁻¹ exists exactly when a material's failed particles can flow (crushed_flow.hpp): the
/// identity for a new run, the checkpoint's on a restart.
template <int D>
void settle_plastic_deformation(Problem<D>& problem) {
  auto& P = problem.particles;
  const bool flows =
      std::any_of(problem.materials.begin(), problem.materials.end(),
                  [](const MaterialSpec& m) { return m.crushed_friction_angle > 0.0; });
  if (!flows)
    P.plastic_inverse.clear();
  else if (P.plastic_inverse.size() != P.size())
    P.plastic_inverse.assign(P.size(), Mat<D>::Identity());
}
}  // namespace

template <int D>
struct Solver<D>::Impl {
  StepState<D> state;
  PhaseFieldWork phase_field_work;

  explicit Impl(Problem<D> p) {
    StepState<D>& s = state;
    s.problem = std::move(p);
    settle_affine(s.problem);
    settle_plastic_deformation(s.problem);
    const Problem<D>& problem = s.problem;
    for (const auto& m : problem.materials) {
      s.models.push_back({m.bulk_modulus, m.shear_modulus});
      s.elastic_laws.push_back(elastic_law(m));
      const bool phase_field = std::holds_alternative<PhaseField>(m.damage);
      s.material_damages.push_back(phase_field ? material_phase_field : (m.damages() ? 1 : 0));
      s.plan.phase_field = s.plan.phase_field || phase_field;
      const auto* rankine = std::get_if<RankineSoftening>(&m.damage);
      s.material_nonlocal.push_back(rankine && rankine->nonlocal ? 1 : 0);
      s.nonlocal_damage = s.nonlocal_damage || s.material_nonlocal.back();
      if (m.damages()) s.plan.damage = true;
      if (m.crushed_friction_angle > 0.0 &&
          (m.degradation != Degradation::hencky_spectral || phase_field || !m.damages()))
        throw std::invalid_argument("material '" + m.name +
                                    "': crushed_friction_angle needs a damage law with "
                                    "degradation = \"hencky-spectral\"");
      s.material_failed_fluid.push_back(
          m.damages() && !phase_field && kept_shear_fraction(m.degradation, 1.0) == 0.0 ? 1 : 0);
      s.crushed_sine.push_back(m.crushed_friction_angle > 0.0 ? std::sin(m.crushed_friction_angle)
                                                              : 0.0);
      s.departure_speed_limit = std::max(
          s.departure_speed_limit, departure_speed_factor * s.models.back().wave_speed(m.density));
    }
    s.plan.partitioned = partitioning_active(problem);
    s.plan.by_bodies = problem.contact.partitioning == Partitioning::bodies;
    // Adhesion ([NBS18] eq. (24)) and contact conductance ([XLS21] eq. (12)-(13)) scale with the
    // contact area.
    s.plan.needs_contact_area =
        std::holds_alternative<AdhesiveFriction>(problem.contact.friction) ||
        problem.thermal.active();
    s.plan.gap_test = problem.contact.position_gap_test;
    s.plan.wall_gap_test = std::any_of(problem.walls.begin(), problem.walls.end(),
                                       [](const WallSpec<D>& w) { return w.gap_test; });
    s.plan.books_contact = s.plan.partitioned || !problem.walls.empty();
    s.plan.books_strain_gap = problem.time.transfer != Transfer::apic &&
                              problem.time.pic_fraction < 1.0 && problem.time.damping == 0.0;
    s.plan.principal_rule = problem.contact.nodal_gradient == NodalGradientRule::principal;
    s.kernel_radius = problem.grid.cell_size * std::sqrt(double(D));
    s.grid.origin = problem.grid.min;
    s.grid.cell_size = problem.grid.cell_size;
    s.grid.inverse_cell_size = 1.0 / problem.grid.cell_size;
    double lightest = std::numeric_limits<double>::infinity();
    for (double m : problem.particles.mass) lightest = std::min(lightest, m);
    s.negligible_mass = std::isfinite(lightest) ? negligible_node_mass_fraction * lightest : 0.0;
    if (!problem.loads.empty()) s.load_force.assign(problem.particles.size(), Vec<D>::Zero());
    for (const auto& w : problem.walls) s.penalty_walls |= w.kind == WallKind::penalty;
    if (problem.thermal.active()) start_thermal();
    if (s.plan.phase_field) start_phase_field();
    compute_initial_state();
  }

  /// The phase-field state with each material's coefficients, and the first solve when the scene
  /// starts with a history field (an initial crack, [KT19] §5.1): the initial state then holds
  /// its d, stress and crack energy.
  void start_phase_field() {
    StepState<D>& s = state;
    s.phase_field = std::make_unique<PhaseFieldState<D>>();
    PhaseFieldState<D>& pf = *s.phase_field;
    const std::size_t materials = s.problem.materials.size();
    for (auto* v : {&pf.local_coefficient, &pf.gradient_coefficient, &pf.drive_factor,
                    &pf.residual_stiffness, &pf.fracture_energy, &pf.length_scale})
      v->assign(materials, 0.0);
    pf.anisotropic.assign(materials, 0);
    pf.fourth_order.assign(materials, Eigen::Matrix3d::Zero());
    for (std::size_t m = 0; m < materials; ++m)
      if (const auto* law = std::get_if<PhaseField>(&s.problem.materials[m].damage)) {
        pf.local_coefficient[m] = law->fracture_energy / (4.0 * law->length_scale);
        pf.gradient_coefficient[m] = law->fracture_energy * law->length_scale;
        pf.drive_factor[m] = 1.0 - law->residual_stiffness;
        pf.residual_stiffness[m] = law->residual_stiffness;
        pf.fracture_energy[m] = law->fracture_energy;
        pf.length_scale[m] = law->length_scale;
        if (law->anisotropic) {
          // The fourth-order term needs the second derivatives of a C¹ basis (scene_fracture.cpp
          // refuses the other kernels and 3D has no Voigt form here).
          if (D != 2 || s.problem.grid.shape_function != ShapeFunctionKind::bspline2)
            throw std::invalid_argument(
                "material '" + s.problem.materials[m].name +
                "': the anisotropic phase field needs shape_function = \"bspline2\" in 2D");
          pf.anisotropic[m] = 1;
          const double l0 = law->length_scale;
          pf.fourth_order[m] =
              law->fracture_energy * l0 * l0 * l0 * phase_field_anisotropy_global(law->anisotropy);
        }
      }
    s.totals.fracture_energy = 0.0;
    const auto& P = s.problem.particles;
    const bool history = std::any_of(P.damage_history.begin(), P.damage_history.end(),
                                     [](double h) { return h > 0.0; });
    // A particle outside the domain fails the first step with its diagnostic; no solve before.
    if (history && !update_active_region(s)) {
      bin_particles_into_strips(s);
      phase_field_for_kind();
    }
  }

  /// The phase-field solve for the scene's shape function.
  void phase_field_for_kind() {
    const auto start = std::chrono::steady_clock::now();
    solve_phase_field_for_kind();
    phase_field_work.seconds +=
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    ++phase_field_work.runs;
    phase_field_work.iterations += state.phase_field->iterations;
    phase_field_work.direct_runs += state.phase_field->direct ? 1 : 0;
    phase_field_work.multigrid_solves +=
        state.phase_field->multigrid && !state.phase_field->direct ? 1 : 0;
    phase_field_work.kept_levels +=
        state.phase_field->multigrid && !state.phase_field->direct && state.phase_field->levels_kept
            ? 1
            : 0;
    phase_field_work.stopped_at_limit += state.phase_field->stopped_at_limit ? 1 : 0;
    phase_field_work.past_limit += state.phase_field->went_past_limit ? 1 : 0;
    if (state.phase_field->stopped_at_limit || state.phase_field->went_past_limit)
      phase_field_work.factorisation_iterations = std::max(
          phase_field_work.factorisation_iterations, state.phase_field->factorisation_iterations);
    phase_field_work.reused_orderings +=
        state.phase_field->direct && state.phase_field->pattern_reused ? 1 : 0;
  }
  void solve_phase_field_for_kind() {
    switch (state.problem.grid.shape_function) {
      case ShapeFunctionKind::linear:
        solve_phase_field<D, ShapeFunctionKind::linear>(state);
        break;
      case ShapeFunctionKind::ugimp:
        solve_phase_field<D, ShapeFunctionKind::ugimp>(state);
        break;
      case ShapeFunctionKind::cpdi:
        solve_phase_field<D, ShapeFunctionKind::cpdi>(state);
        break;
      case ShapeFunctionKind::bspline2:
        solve_phase_field<D, ShapeFunctionKind::bspline2>(state);
        break;
    }
  }

  void start_thermal() {
    state.thermal = std::make_unique<ThermalState<D>>(state.problem);
    if (state.plan.damage) state.degradable.assign(state.problem.particles.size(), 0.0);
    // F_p⁻¹ exists exactly when failed material can flow (settle_plastic_deformation).
    if (!state.problem.particles.plastic_inverse.empty())
      state.flow_heat.assign(state.problem.particles.size(), 0.0);
  }

  /// Stress and stored energy of the current F and d (no damage growth), and the series row of
  /// that state.
  template <bool Thermal>
  void compute_initial_state() {
    StepState<D>& s = state;
    const auto& P = s.problem.particles;
    double kinetic = 0.0, strain = 0.0;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    const bool affine = s.problem.time.transfer == Transfer::apic;
    const ShapeFunctionKind kind = s.problem.grid.shape_function;
    if (s.plan.damage) s.release_before.assign(P.size(), 0.0);
#pragma omp parallel for reduction(+ : kinetic, strain) schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      strain += P.volume0[p] * update_constitutive<D, Thermal, false>(s, p, 0.0).stored;
      kinetic += 0.5 * P.mass[p] * P.v[p].squaredNorm();
      if (affine)
        kinetic += affine_kinetic_energy<D>(
            P.mass[p], P.affine[p], domain_second_moment<D>(P, static_cast<std::size_t>(p), kind));
    }
    const double fracture_energy = s.totals.fracture_energy;  // of the initial phase-field solve
    s.totals = EnergyAccumulators{};
    s.totals.fracture_energy = fracture_energy;
    s.totals.initial_energy = kinetic + strain + fracture_energy;
    s.row = SeriesRow<D>{};
    s.row.kinetic = kinetic;
    s.row.strain = strain;
    s.row.thermal = thermal_energy<D>(s.problem, P);
    s.row.totals = s.totals;
    s.row.momentum = Vec<D>::Zero();
    s.row.angular_momentum = Axial<D>::Zero();
    for (std::size_t p = 0; p < P.size(); ++p) {
      s.row.momentum += P.mass[p] * P.v[p];
      s.row.angular_momentum += P.mass[p] * cross<D>(P.x[p], P.v[p]);
      if (affine)
        s.row.angular_momentum +=
            P.mass[p] * axial<D>(P.affine[p] * domain_second_moment<D>(P, p, kind));
    }
    s.row.wall_force.assign(s.problem.walls.size(), Vec<D>::Zero());
    s.row.wall_displacement.assign(s.problem.walls.size(), Vec<D>::Zero());
    s.next_dt_limit = stable_time_step<D>(s.problem, P, s.problem.time.cfl);
  }
  void compute_initial_state() {
    state.thermal ? compute_initial_state<true>() : compute_initial_state<false>();
  }

  /// The step, written once: every stage a scene does not need is compiled out (Partitioned,
  /// Thermal) or skipped by the plan fixed at setup.
  template <ShapeFunctionKind Kind, bool Partitioned, bool Thermal, bool Affine>
  std::optional<NumericalFailure> advance(double dt) {
    StepState<D>& s = state;
    if constexpr (Partitioned) partition_nodes<D, Kind>(s);
    scatter_to_grid<D, Kind, Partitioned, Affine>(s);
    if constexpr (Thermal) thermal_begin<D, Kind, Partitioned>(s);  // nodal θⁿ for friction
    update_grid_velocities(s, dt);
    const double friction_before = s.totals.friction_work, wall_work_before = s.totals.wall_work;
    if constexpr (Partitioned) exchange_contact_momentum(s, dt);
    if (!s.problem.walls.empty()) apply_walls(s, dt);
    if (s.plan.books_contact) book_contact_energy(s, dt, friction_before, wall_work_before);
    if constexpr (Thermal) thermal_finish<D, Kind, Partitioned>(s, dt);  // [XLS21] Alg. 1
    const double kinetic_from_nodes = s.row.kinetic + nodal_kinetic_energy_change(s, dt);
    auto failure = grid_to_particles<D, Kind, Partitioned, Thermal, Affine>(s, dt);
    if (!failure) {
      s.totals.transfer_dissipation += kinetic_from_nodes - s.row.kinetic;
      // The strain side of the transfer gap (transfer_energy.cpp).
      if (s.plan.books_strain_gap)
        s.totals.transfer_dissipation +=
            (1.0 - s.problem.time.pic_fraction) * (s.strain_gap.nodal - s.strain_gap.particles);
    }
    return failure;
  }

  template <ShapeFunctionKind Kind, bool Affine>
  std::optional<NumericalFailure> advance_with_modules(double dt) {
    const bool partitioned = state.partition.this_step;
    if (state.thermal)
      return partitioned ? advance<Kind, true, true, Affine>(dt)
                         : advance<Kind, false, true, Affine>(dt);
    return partitioned ? advance<Kind, true, false, Affine>(dt)
                       : advance<Kind, false, false, Affine>(dt);
  }
  template <ShapeFunctionKind Kind>
  std::optional<NumericalFailure> advance_with_modules(double dt) {
    return state.problem.time.transfer == Transfer::apic ? advance_with_modules<Kind, true>(dt)
                                                         : advance_with_modules<Kind, false>(dt);
  }

  std::optional<NumericalFailure> take_step(double dt_cap) {
    StepState<D>& s = state;
    const double dt =
        std::min(s.problem.time.fixed_dt > 0.0 ? s.problem.time.fixed_dt : s.next_dt_limit, dt_cap);
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      NumericalFailure failure{s.step, s.time, -1,
                               "time step is not positive and finite (dt = " + format_number(dt) +
                                   " s): the particles have no finite wave speed"};
      return failure;
    }
    if (auto failure = update_active_region(s)) return failure;
    bin_particles_into_strips(s);
    // [KT19] Alg. 1: the phase field from the history of the last step first, so that the damage
    // field of the partition and this step's stresses see its d.
    if (s.plan.phase_field) phase_field_for_kind();
    s.partition.this_step = s.plan.by_bodies;
    if (s.plan.partitioned && !s.plan.by_bodies) update_damage_field(s);
    size_grid(s);
    if (!s.load_force.empty()) update_load_forces(s);
    if (s.penalty_walls) apply_penalty_walls(s);
    std::optional<NumericalFailure> failure;
    switch (s.problem.grid.shape_function) {
      case ShapeFunctionKind::linear:
        failure = advance_with_modules<ShapeFunctionKind::linear>(dt);
        break;
      case ShapeFunctionKind::ugimp:
        failure = advance_with_modules<ShapeFunctionKind::ugimp>(dt);
        break;
      case ShapeFunctionKind::cpdi:
        failure = advance_with_modules<ShapeFunctionKind::cpdi>(dt);
        break;
      case ShapeFunctionKind::bspline2:
        failure = advance_with_modules<ShapeFunctionKind::bspline2>(dt);
        break;
    }
    if (failure) return failure;
    if (s.thermal) s.next_dt_limit = std::min(s.next_dt_limit, s.thermal->dt_limit);
    if (s.problem.grid.outside == OutsidePolicy::remove)
      if (auto departed = remove_departed_particles(s, dt)) return departed;
    if (s.thermal) s.row.thermal = thermal_energy<D>(s.problem, s.problem.particles);
    s.time += dt;
    ++s.step;
    SeriesRow<D>& row = s.row;
    row.step = s.step;
    row.time = s.time;
    row.dt = dt;
    row.totals = s.totals;
    row.balance_error =
        (row.kinetic + row.strain + s.totals.fracture_energy + s.totals.dissipated +
         s.totals.flow_dissipation + s.totals.friction_work + s.totals.contact_dissipation +
         s.totals.transfer_dissipation + s.totals.lost.kinetic + s.totals.lost.strain) -
        (s.totals.initial_energy + s.totals.wall_work + s.totals.gravity_work + s.totals.load_work +
         s.totals.history_excess);
    for (std::size_t w = 0; w < s.problem.walls.size(); ++w)
      row.wall_displacement[w] = s.problem.walls[w].velocity.displacement(s.time);
    return std::nullopt;
  }
};

template <int D>
Solver<D>::Solver(Problem<D> problem) : impl_(std::make_unique<Impl>(std::move(problem))) {}
template <int D>
Solver<D>::~Solver() = default;
template <int D>
Solver<D>::Solver(Solver&&) noexcept = default;
template <int D>
Solver<D>& Solver<D>::operator=(Solver&&) noexcept = default;

template <int D>
std::optional<NumericalFailure> Solver<D>::step(double dt_cap) {
  return impl_->take_step(dt_cap);
}
template <int D>
const Problem<D>& Solver<D>::problem() const {
  return impl_->state.problem;
}
template <int D>
const Particles<D>& Solver<D>::particles() const {
  return impl_->state.problem.particles;
}
template <int D>
Particles<D>& Solver<D>::particles() {
  return impl_->state.problem.particles;
}
template <int D>
double Solver<D>::time() const {
  return impl_->state.time;
}
template <int D>
long long Solver<D>::step_count() const {
  return impl_->state.step;
}
template <int D>
const EnergyAccumulators& Solver<D>::accumulators() const {
  return impl_->state.totals;
}
template <int D>
const SeriesRow<D>& Solver<D>::last_row() const {
  return impl_->state.row;
}
template <int D>
Vec<D> Solver<D>::wall_displacement(std::size_t wall) const {
  return impl_->state.problem.walls.at(wall).velocity.displacement(impl_->state.time);
}
template <int D>
double Solver<D>::stable_dt() const {
  return impl_->state.next_dt_limit;
}
template <int D>
const PhaseFieldWork& Solver<D>::phase_field_work() const {
  return impl_->phase_field_work;
}

template <int D>
void Solver<D>::set_phase_field_iteration_limit(int limit, bool weigh_factorisation) {
  if (!impl_->state.phase_field) return;
  impl_->state.phase_field->iteration_limit = std::max(limit, 1);
  impl_->state.phase_field->weigh_factorisation = weigh_factorisation;
}

template <int D>
void Solver<D>::set_phase_field_preconditioner(PhaseFieldPreconditioner choice) {
  if (impl_->state.phase_field) impl_->state.phase_field->preconditioner = choice;
}

template <int D>
PhaseFieldWarmStart<D> Solver<D>::phase_field_warm_start() const {
  return impl_->state.phase_field ? impl_->state.phase_field->last : PhaseFieldWarmStart<D>{};
}

template <int D>
void Solver<D>::restore(double time, long long step, const EnergyAccumulators& totals,
                        Particles<D> particles, PhaseFieldWarmStart<D> phase_field) {
  Problem<D>& problem = impl_->state.problem;
  if (particles.id.size() != particles.size()) {  // a state saved before particles had ids
    particles.id.resize(particles.size());
    std::iota(particles.id.begin(), particles.id.end(), 0);
  }
  // Loads list particles by their index at step 0, which is the id of a particle in a state from
  // which particles have been removed.
  std::vector<std::int64_t> new_index(problem.particles.size(), -1);
  for (std::size_t p = 0; p < particles.size(); ++p)
    new_index.at(static_cast<std::size_t>(particles.id[p])) = static_cast<std::int64_t>(p);
  remap_particle_references(problem, new_index);
  problem.particles = std::move(particles);
  if (!impl_->state.load_force.empty()) impl_->state.load_force.resize(problem.particles.size());
  settle_affine(problem);
  if (impl_->state.thermal) impl_->start_thermal();
  // The constructor's solve (from the scene's initial history) is replaced by the checkpoint's.
  // The multigrid levels the solver holds are not those of the carried system: the next solve
  // that keeps levels builds them from it (step/phase_field_solve.cpp).
  if (impl_->state.phase_field) {
    impl_->state.phase_field->last = std::move(phase_field);
    impl_->state.phase_field->levels_held = false;
  }
  impl_->compute_initial_state();
  impl_->state.time = time;
  impl_->state.step = step;
  impl_->state.totals = totals;
  impl_->state.row.step = step;
  impl_->state.row.time = time;
  impl_->state.row.totals = totals;
}

template class Solver<2>;
template class Solver<3>;

}  // namespace fragmpm::mpm
