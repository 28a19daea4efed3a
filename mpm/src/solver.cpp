// The explicit MPM step: P2G, grid update, rigid walls, G2P with FLIP/PIC blend, update-stress-last.
#include "fragmpm/mpm/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "fragmpm/mpm/grid_index.hpp"
#include "fragmpm/mpm/neo_hookean.hpp"
#include "fragmpm/mpm/shape_functions.hpp"

namespace fragmpm::mpm {

namespace {

template <int D>
std::string format_vector(const Vec<D>& v) {
  std::ostringstream out;
  out.precision(6);
  out << "(";
  for (int k = 0; k < D; ++k) out << (k ? ", " : "") << v[k];
  out << ")";
  return out.str();
}

template <int D>
std::string format_matrix(const Mat<D>& m) {
  std::ostringstream out;
  out.precision(6);
  out << "[";
  for (int i = 0; i < D; ++i) {
    out << (i ? "; " : "");
    for (int j = 0; j < D; ++j) out << (j ? " " : "") << m(i, j);
  }
  out << "]";
  return out.str();
}

/// Nodes lighter than this fraction of the lightest particle carry no velocity: their mass comes
/// from the far tail of a shape function, and dividing by it would amplify round-off.
constexpr double negligible_node_mass_fraction = 1e-10;

}  // namespace

template <int D>
std::vector<ModuleDecision> plan_modules(const Problem<D>& problem) {
  std::vector<ModuleDecision> plan;
  const char* shape = problem.grid.shape_function == ShapeFunctionKind::cpdi     ? "CPDI"
                      : problem.grid.shape_function == ShapeFunctionKind::ugimp ? "uGIMP"
                                                                                : "linear";
  plan.push_back({"mechanics", true, std::string("explicit update-stress-last MPM with ") + shape +
                                         " shape functions, neo-Hookean bodies"});
  plan.push_back({"walls", !problem.walls.empty(),
                  problem.walls.empty() ? "no walls in the scene"
                                        : std::to_string(problem.walls.size()) + " rigid wall(s)"});
  plan.push_back({"gravity", problem.gravity.squaredNorm() > 0.0,
                  problem.gravity.squaredNorm() > 0.0 ? "gravity set in [physics]" : "no gravity"});
  const std::size_t bodies = problem.body_names.size();
  plan.push_back({"partitioning", false,
                  bodies > 1 ? std::to_string(bodies) +
                                   " bodies share one velocity field (multi-field contact is not "
                                   "part of this build yet)"
                             : "one body and no damage: one velocity field, no neighbour search"});
  plan.push_back({"damage", false, "no damage law in the scene"});
  plan.push_back({"thermal", false, "no thermal data and no heat sources: no thermal arrays"});
  return plan;
}

template <int D>
double stable_time_step(const Problem<D>& problem, const Particles<D>& particles, double cfl) {
  std::vector<NeoHookean> models;
  for (const auto& m : problem.materials) models.push_back({m.bulk_modulus, m.shear_modulus});
  double max_speed = 0.0;
  const std::int64_t n = static_cast<std::int64_t>(particles.size());
#pragma omp parallel for reduction(max : max_speed) schedule(static)
  for (std::int64_t p = 0; p < n; ++p) {
    const double J = particles.F[p].determinant();
    const double density = particles.mass[p] / (particles.volume0[p] * J);
    const double c = models[particles.material[p]].wave_speed(density);
    max_speed = std::max(max_speed, c + particles.v[p].norm());
  }
  if (max_speed <= 0.0) return std::numeric_limits<double>::infinity();
  // Multilinear hats with a lumped mass: the stiffest grid mode of a cell has ω = 2c√D/h, so
  // central-difference stepping is stable for Δt < 2/ω = h/(c√D). The DESIGN's h/c is the 1D value
  // and lets a 2D scene run unstably at C_cfl close to 1.
  return cfl * problem.grid.cell_size / (std::sqrt(double(D)) * max_speed);
}

template <int D>
struct Solver<D>::Impl {
  Problem<D> problem;
  std::vector<NeoHookean> models;
  double time = 0.0;
  long long step = 0;
  EnergyAccumulators totals;
  SeriesRow<D> row;
  double next_dt_limit = 0.0;  ///< CFL limit from the state after the last step (C_cfl included)
  double negligible_mass = 0.0;

  GridIndex<D> grid;
  std::vector<double> node_mass;
  std::vector<Vec<D>> node_momentum, node_force, node_velocity_lumped, node_velocity;
  // Race-free, thread-count-independent scatter: particles are binned into strips along direction 0
  // that are wider than twice any stencil's reach, so strips of equal parity never share a node.
  // Even strips scatter in parallel, then odd ones; within a strip particles go in index order, so
  // every node sums its contributions in the same order whatever the number of threads.
  std::int64_t strip_width = 3;         ///< cells per strip
  double largest_half_extent = 0.0;     ///< largest stencil half-extent along direction 0 [cells]
  std::vector<std::int64_t> strip_start, strip_order, strip_of;
  int thread_slots = 1;
  IVec<D> domain_nodes;  ///< number of cells of the computational domain per direction

  explicit Impl(Problem<D> p) : problem(std::move(p)) {
    for (const auto& m : problem.materials) models.push_back({m.bulk_modulus, m.shear_modulus});
    grid.origin = problem.grid.min;
    grid.cell_size = problem.grid.cell_size;
    grid.inverse_cell_size = 1.0 / problem.grid.cell_size;
    for (int k = 0; k < D; ++k)
      domain_nodes[k] = static_cast<std::int64_t>(
          std::llround((problem.grid.max[k] - problem.grid.min[k]) / problem.grid.cell_size));
    double lightest = std::numeric_limits<double>::infinity();
    for (double m : problem.particles.mass) lightest = std::min(lightest, m);
    negligible_mass = std::isfinite(lightest) ? negligible_node_mass_fraction * lightest : 0.0;
    compute_stress_and_energy_of_initial_state();
  }

  void compute_stress_and_energy_of_initial_state() {
    auto& P = problem.particles;
    double kinetic = 0.0, strain = 0.0;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
#pragma omp parallel for reduction(+ : kinetic, strain) schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const NeoHookean& model = models[P.material[p]];
      P.stress[p] = model.cauchy<D>(P.F[p]);
      strain += P.volume0[p] * model.energy_density<D>(P.F[p]);
      kinetic += 0.5 * P.mass[p] * P.v[p].squaredNorm();
    }
    totals = EnergyAccumulators{};
    totals.initial_energy = kinetic + strain;
    row = SeriesRow<D>{};
    row.kinetic = kinetic;
    row.strain = strain;
    row.totals = totals;
    row.momentum = total_momentum();
    row.wall_force.assign(problem.walls.size(), Vec<D>::Zero());
    row.wall_displacement.assign(problem.walls.size(), Vec<D>::Zero());
    next_dt_limit = stable_time_step<D>(problem, P, problem.time.cfl);
  }

  Vec<D> total_momentum() const {
    const auto& P = problem.particles;
    Vec<D> sum = Vec<D>::Zero();
    for (std::size_t p = 0; p < P.size(); ++p) sum += P.mass[p] * P.v[p];
    return sum;
  }

  double choose_dt() const {
    return problem.time.fixed_dt > 0.0 ? problem.time.fixed_dt : next_dt_limit;
  }

  /// Active region = nodes touched by any particle's stencil, plus one node of padding.
  std::optional<NumericalFailure> update_active_region() {
    const auto& P = problem.particles;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    Vec<D> lower = Vec<D>::Constant(std::numeric_limits<double>::infinity());
    Vec<D> upper = -lower;
    std::int64_t outside = -1;
    double largest = 0.0;
    const Vec<D> domain_min = problem.grid.min, domain_max = problem.grid.max;
    const ShapeFunctionKind kind = problem.grid.shape_function;
#pragma omp parallel
    {
      Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
      double half_extent = 0.0;
      std::int64_t first_outside = -1;
#pragma omp for schedule(static) nowait
      for (std::int64_t p = 0; p < n; ++p) {
        Vec<D> a = P.x[p], b = P.x[p];
        stencil_bounds<D>(kind, P.x[p], P.domain[p], 0.5 * P.domain[p].diagonal().cwiseAbs(), a, b);
        lo = lo.cwiseMin(a);
        hi = hi.cwiseMax(b);
        half_extent = std::max(half_extent, 0.5 * (b[0] - a[0]));
        if (first_outside < 0 && ((P.x[p] - domain_min).minCoeff() < 0.0 ||
                                  (domain_max - P.x[p]).minCoeff() < 0.0 || !P.x[p].allFinite()))
          first_outside = p;
      }
#pragma omp critical(fragmpm_active_region)
      {
        lower = lower.cwiseMin(lo);
        upper = upper.cwiseMax(hi);
        largest = std::max(largest, half_extent);
        if (first_outside >= 0 && (outside < 0 || first_outside < outside)) outside = first_outside;
      }
    }
    if (outside >= 0) {
      NumericalFailure failure;
      failure.step = step;
      failure.time = time;
      failure.particle = outside;
      failure.what = "particle " + std::to_string(outside) + " (body " +
                     std::to_string(P.body[outside]) + ") left the computational domain: x = " +
                     format_vector<D>(P.x[outside]) + " m, domain " + format_vector<D>(domain_min) +
                     " to " + format_vector<D>(domain_max) + " m, v = " +
                     format_vector<D>(P.v[outside]) + " m/s";
      return failure;
    }
    for (int k = 0; k < D; ++k) {
      std::int64_t first = static_cast<std::int64_t>(
                               std::floor((lower[k] - grid.origin[k]) * grid.inverse_cell_size)) - 1;
      std::int64_t last = static_cast<std::int64_t>(
                              std::floor((upper[k] - grid.origin[k]) * grid.inverse_cell_size)) + 2;
      grid.lower[k] = first;
      grid.extent[k] = last - first + 1;
    }
    largest_half_extent = largest * grid.inverse_cell_size;
    return std::nullopt;
  }

  void resize_grid() {
    const std::size_t nodes = static_cast<std::size_t>(grid.node_count());
    node_mass.assign(nodes, 0.0);
    node_momentum.assign(nodes, Vec<D>::Zero());
    node_force.assign(nodes, Vec<D>::Zero());
    node_velocity_lumped.resize(nodes);
    node_velocity.resize(nodes);
    thread_slots = omp_get_max_threads();
  }

  /// Counting sort of particles into strips (stable: index order within a strip).
  void bin_particles_into_strips() {
    const auto& P = problem.particles;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    // A particle in cell c touches nodes c − ceil(e) … c + ceil(e) + 1 for half-extent e (cells).
    strip_width = 2 * static_cast<std::int64_t>(std::ceil(largest_half_extent)) + 2;
    const std::int64_t strips = (grid.extent[0] + strip_width - 1) / strip_width;
    strip_start.assign(static_cast<std::size_t>(strips + 1), 0);
    strip_of.resize(static_cast<std::size_t>(n));
    strip_order.resize(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      const std::int64_t cell = static_cast<std::int64_t>(
          std::floor((P.x[p][0] - grid.origin[0]) * grid.inverse_cell_size)) - grid.lower[0];
      strip_of[p] = std::clamp<std::int64_t>(cell / strip_width, 0, strips - 1);
    }
    for (std::int64_t p = 0; p < n; ++p) ++strip_start[strip_of[p] + 1];
    for (std::int64_t s = 0; s < strips; ++s) strip_start[s + 1] += strip_start[s];
    std::vector<std::int64_t>& cursor = strip_cursor;
    cursor.assign(strip_start.begin(), strip_start.end() - 1);
    for (std::int64_t p = 0; p < n; ++p) strip_order[cursor[strip_of[p]]++] = p;
  }
  std::vector<std::int64_t> strip_cursor;


  template <ShapeFunctionKind Kind>
  static void fill_stencil(const Particles<D>& P, std::int64_t p, const GridIndex<D>& g,
                           Stencil<D>& s) {
    if constexpr (Kind == ShapeFunctionKind::linear) linear_stencil<D>(P.x[p], g, s);
    else if constexpr (Kind == ShapeFunctionKind::ugimp)
      ugimp_stencil<D>(P.x[p], 0.5 * P.domain[p].diagonal().cwiseAbs(), g, s);
    else cpdi_stencil<D>(P.x[p], P.domain[p], g, s);
  }

  /// 000 eq. (47)-(49): m_i = Σ S̄ m_p, p_i = Σ S̄ m_p v_p, f_i = Σ S̄ m_p g − Σ V_p σ_p ∇S̄.
  template <ShapeFunctionKind Kind>
  void particles_to_grid() {
    const auto& P = problem.particles;
    const Vec<D> gravity = problem.gravity;
    bin_particles_into_strips();
    const std::int64_t strips = static_cast<std::int64_t>(strip_start.size()) - 1;
    for (std::int64_t parity = 0; parity < 2; ++parity) {
#pragma omp parallel
      {
        Stencil<D> s;
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t strip = parity; strip < strips; strip += 2) {
          for (std::int64_t k = strip_start[strip]; k < strip_start[strip + 1]; ++k) {
            const std::int64_t p = strip_order[k];
            fill_stencil<Kind>(P, p, grid, s);
            const double volume = P.volume0[p] * P.F[p].determinant();
            const Mat<D> volume_stress = volume * P.stress[p];
            const Vec<D> momentum = P.mass[p] * P.v[p];
            const Vec<D> weight_force = P.mass[p] * gravity;
            for (int e = 0; e < s.count; ++e) {
              const std::size_t i = static_cast<std::size_t>(s.node[e]);
              node_mass[i] += s.weight[e] * P.mass[p];
              node_momentum[i] += s.weight[e] * momentum;
              node_force[i] += s.weight[e] * weight_force - volume_stress * s.gradient[e];
            }
          }
        }
      }
    }
  }

  void update_grid_velocities(double dt) {
    const std::int64_t nodes = static_cast<std::int64_t>(node_mass.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < nodes; ++i) {
      if (node_mass[i] > negligible_mass) {
        node_velocity_lumped[i] = node_momentum[i] / node_mass[i];
        node_velocity[i] = node_velocity_lumped[i] + dt * node_force[i] / node_mass[i];
      } else {
        node_velocity_lumped[i].setZero();
        node_velocity[i].setZero();
      }
    }
  }

  /// Rigid walls (004 §2.12: the material side takes the wall's velocity where it approaches).
  /// Node impulses J give each wall's reaction force and the wall work Σ J·v_wall. Friction work is
  /// the tangential force times the slip it acts over, Σ |J_t|·|u_t| with u_t the slip velocity
  /// left after the step: an energy measured with impulses, which FLIP transfers exactly, rather
  /// than with nodal kinetic energies, which it does not.
  void apply_walls(double dt) {
    const std::int64_t nodes = static_cast<std::int64_t>(node_mass.size());
    const double tolerance = 1e-9 * grid.cell_size;
    for (std::size_t w = 0; w < problem.walls.size(); ++w) {
      const WallSpec<D>& wall = problem.walls[w];
      const Vec<D> wall_velocity = wall.velocity.velocity(time + dt);
      const Vec<D> wall_point = wall.point + wall.velocity.displacement(time + dt);
      Vec<D> impulse_sum = Vec<D>::Zero();
      double work = 0.0, friction = 0.0;
      // Serial and in node order: few nodes pass the plane test, and the sums must not depend on
      // the thread count.
      for (std::int64_t i = 0; i < nodes; ++i) {
        const double m = node_mass[i];
        if (m <= negligible_mass) continue;
        const Vec<D> X = grid.position(grid.global(i));
        if ((X - wall_point).dot(wall.normal) > tolerance) continue;  // in front of the wall
        const Vec<D> relative = node_velocity[i] - wall_velocity;
        const double approach = relative.dot(wall.normal);
        const Vec<D> tangential = relative - approach * wall.normal;
        Vec<D> change = Vec<D>::Zero();
        switch (wall.kind) {
          case WallKind::fixed: change = -relative; break;
          case WallKind::roller: change = -approach * wall.normal; break;
          case WallKind::contact: {
            if (approach >= 0.0) continue;  // separating: no contact
            change = -approach * wall.normal;
            const double slip = tangential.norm();
            if (slip > 0.0) {
              // Coulomb: the tangential velocity change is limited by μ times the normal one.
              const double fraction = std::min(
                  1.0, std::get<CoulombFriction>(wall.friction).coefficient * (-approach) / slip);
              change -= fraction * tangential;
              friction += m * fraction * slip * (1.0 - fraction) * slip;
            }
            break;
          }
        }
        node_velocity[i] += change;
        impulse_sum += m * change;
        work += m * change.dot(wall_velocity);
      }
      row.wall_force[w] = -impulse_sum / dt;  // force of the material on the wall
      totals.wall_work += work;
      totals.friction_work += friction;
    }
  }

  /// G2P (000 eq. 64-66) and the stress update that closes the step (update-stress-last).
  template <ShapeFunctionKind Kind>
  std::optional<NumericalFailure> grid_to_particles(double dt) {
    auto& P = problem.particles;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    const double pic = problem.time.pic_fraction;
    const bool deform_domain = Kind == ShapeFunctionKind::cpdi;
    const Vec<D> gravity = problem.gravity;
    double kinetic = 0.0, strain = 0.0, gravity_work = 0.0, max_speed = 0.0;
    std::int64_t failed = -1;
    std::vector<double> momentum_parts(static_cast<std::size_t>(D) * thread_slots, 0.0);
#pragma omp parallel reduction(+ : kinetic, strain, gravity_work) reduction(max : max_speed)
    {
      Stencil<D> s;
      Vec<D> momentum = Vec<D>::Zero();
      std::int64_t first_failed = -1;
#pragma omp for schedule(static) nowait
      for (std::int64_t p = 0; p < n; ++p) {
        fill_stencil<Kind>(P, p, grid, s);
        Vec<D> v_pic = Vec<D>::Zero(), v_change = Vec<D>::Zero();
        Mat<D> velocity_gradient = Mat<D>::Zero();
        for (int e = 0; e < s.count; ++e) {
          const std::size_t i = static_cast<std::size_t>(s.node[e]);
          v_pic += s.weight[e] * node_velocity[i];
          v_change += s.weight[e] * (node_velocity[i] - node_velocity_lumped[i]);
          velocity_gradient += node_velocity[i] * s.gradient[e].transpose();
        }
        const Vec<D> displacement = dt * v_pic;
        P.x[p] += displacement;
        P.v[p] = (1.0 - pic) * (P.v[p] + v_change) + pic * v_pic;
        // 000 eq. (66) updates F with I + Δt L, which stretches a rigidly rotating body by (ωΔt)² per
        // step (a spinning disk builds up stress). The midpoint (Hughes–Winget) increment
        // (I − ΔtL/2)⁻¹(I + ΔtL/2) agrees to O(Δt²) and is exactly orthogonal for a spin.
        const Mat<D> half_step = 0.5 * dt * velocity_gradient;
        const Mat<D> increment =
            (Mat<D>::Identity() - half_step).inverse() * (Mat<D>::Identity() + half_step);
        P.F[p] = increment * P.F[p];
        if (deform_domain) P.domain[p] = increment * P.domain[p];
        const double J = P.F[p].determinant();
        if (!(J > 0.0) || !P.v[p].allFinite() || !P.F[p].allFinite()) {
          if (first_failed < 0) first_failed = p;
          continue;
        }
        const NeoHookean& model = models[P.material[p]];
        P.stress[p] = model.cauchy<D>(P.F[p]);
        strain += P.volume0[p] * model.energy_density<D>(P.F[p]);
        kinetic += 0.5 * P.mass[p] * P.v[p].squaredNorm();
        gravity_work += P.mass[p] * gravity.dot(displacement);
        momentum += P.mass[p] * P.v[p];
        const double density = P.mass[p] / (P.volume0[p] * J);
        max_speed = std::max(max_speed, model.wave_speed(density) + P.v[p].norm());
      }
      const std::size_t t = static_cast<std::size_t>(omp_get_thread_num());
      for (int k = 0; k < D; ++k) momentum_parts[t * D + k] = momentum[k];
#pragma omp critical(fragmpm_g2p_failure)
      if (first_failed >= 0 && (failed < 0 || first_failed < failed)) failed = first_failed;
    }
    if (failed >= 0) {
      NumericalFailure failure;
      failure.step = step + 1;
      failure.time = time + dt;
      failure.particle = failed;
      failure.what = "particle " + std::to_string(failed) + " (body " +
                     std::to_string(P.body[failed]) + ", material '" +
                     problem.materials[P.material[failed]].name +
                     "') became inverted or non-finite: J = " +
                     std::to_string(P.F[failed].determinant()) + ", F = " +
                     format_matrix<D>(P.F[failed]) + ", x = " + format_vector<D>(P.x[failed]) +
                     " m, v = " + format_vector<D>(P.v[failed]) + " m/s, dt = " +
                     std::to_string(dt) + " s";
      return failure;
    }
    row.momentum.setZero();
    for (std::size_t t = 0; t < static_cast<std::size_t>(thread_slots); ++t)
      for (int k = 0; k < D; ++k) row.momentum[k] += momentum_parts[t * D + k];
    row.kinetic = kinetic;
    row.strain = strain;
    totals.gravity_work += gravity_work;

    next_dt_limit = max_speed > 0.0
                        ? problem.time.cfl * grid.cell_size / (std::sqrt(double(D)) * max_speed)
                        : std::numeric_limits<double>::infinity();
    return std::nullopt;
  }

  template <ShapeFunctionKind Kind>
  std::optional<NumericalFailure> advance(double dt) {
    particles_to_grid<Kind>();
    update_grid_velocities(dt);
    if (!problem.walls.empty()) apply_walls(dt);
    return grid_to_particles<Kind>(dt);
  }

  std::optional<NumericalFailure> take_step(double dt_cap) {
    const double dt = std::min(choose_dt(), dt_cap);
    if (!(dt > 0.0) || !std::isfinite(dt)) {
      NumericalFailure failure{step, time, -1,
                               "time step is not positive and finite (dt = " + std::to_string(dt) +
                                   " s): the particles have no finite wave speed"};
      return failure;
    }
    if (auto failure = update_active_region()) return failure;
    resize_grid();
    std::optional<NumericalFailure> failure;
    switch (problem.grid.shape_function) {
      case ShapeFunctionKind::linear: failure = advance<ShapeFunctionKind::linear>(dt); break;
      case ShapeFunctionKind::ugimp: failure = advance<ShapeFunctionKind::ugimp>(dt); break;
      case ShapeFunctionKind::cpdi: failure = advance<ShapeFunctionKind::cpdi>(dt); break;
    }
    if (failure) return failure;
    time += dt;
    ++step;
    row.step = step;
    row.time = time;
    row.dt = dt;
    row.totals = totals;
    row.balance_error = (row.kinetic + row.strain + totals.dissipated + totals.friction_work) -
                        (totals.initial_energy + totals.wall_work + totals.gravity_work);
    for (std::size_t w = 0; w < problem.walls.size(); ++w)
      row.wall_displacement[w] = problem.walls[w].velocity.displacement(time);
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
std::optional<NumericalFailure> Solver<D>::step(double dt_cap) { return impl_->take_step(dt_cap); }
template <int D>
const Problem<D>& Solver<D>::problem() const { return impl_->problem; }
template <int D>
const Particles<D>& Solver<D>::particles() const { return impl_->problem.particles; }
template <int D>
Particles<D>& Solver<D>::particles() { return impl_->problem.particles; }
template <int D>
double Solver<D>::time() const { return impl_->time; }
template <int D>
long long Solver<D>::step_count() const { return impl_->step; }
template <int D>
const EnergyAccumulators& Solver<D>::accumulators() const { return impl_->totals; }
template <int D>
const SeriesRow<D>& Solver<D>::last_row() const { return impl_->row; }
template <int D>
Vec<D> Solver<D>::wall_displacement(std::size_t wall) const {
  return impl_->problem.walls.at(wall).velocity.displacement(impl_->time);
}
template <int D>
double Solver<D>::stable_dt() const { return impl_->next_dt_limit; }

template <int D>
void Solver<D>::restore(double time, long long step, const EnergyAccumulators& totals,
                        Particles<D> particles) {
  impl_->problem.particles = std::move(particles);
  impl_->compute_stress_and_energy_of_initial_state();
  impl_->time = time;
  impl_->step = step;
  impl_->totals = totals;
  impl_->row.step = step;
  impl_->row.time = time;
  impl_->row.totals = totals;
}

template std::vector<ModuleDecision> plan_modules<2>(const Problem<2>&);
template std::vector<ModuleDecision> plan_modules<3>(const Problem<3>&);
template double stable_time_step<2>(const Problem<2>&, const Particles<2>&, double);
template double stable_time_step<3>(const Problem<3>&, const Particles<3>&, double);
template class Solver<2>;
template class Solver<3>;

}  // namespace fragmpm::mpm
