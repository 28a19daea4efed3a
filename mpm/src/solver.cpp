// The explicit MPM step: P2G, grid update, rigid walls, G2P with FLIP/PIC blend, update-stress-last.
#include "fragmpm/mpm/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "fragmpm/mpm/contact_exchange.hpp"
#include "fragmpm/mpm/damage_field.hpp"
#include "fragmpm/mpm/damage_law.hpp"
#include "fragmpm/mpm/grid_index.hpp"
#include "fragmpm/mpm/neo_hookean.hpp"
#include "fragmpm/mpm/shape_functions.hpp"
#include "fragmpm/mpm/thermal.hpp"
#include "thermal_step.hpp"

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
bool partitioning_active(const Problem<D>& problem) {
  if (problem.contact.partitioning == Partitioning::off) return false;
  if (problem.contact.partitioning == Partitioning::bodies) return true;
  if (problem.body_names.size() > 1) return true;
  for (const auto& m : problem.materials)
    if (m.damages()) return true;
  return false;
}

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
  plan.push_back({"loads", !problem.loads.empty(),
                  problem.loads.empty() ? "no traction loads"
                                        : std::to_string(problem.loads.size()) + " traction load(s)"});
  plan.push_back({"gravity", problem.gravity.squaredNorm() > 0.0,
                  problem.gravity.squaredNorm() > 0.0 ? "gravity set in [physics]" : "no gravity"});
  std::vector<std::string> damaging;
  for (const auto& m : problem.materials)
    if (m.damages()) damaging.push_back(m.name);
  std::string damage_reason = "no damage law in the scene";
  if (!damaging.empty()) {
    damage_reason = "damage law on material(s)";
    for (const auto& name : damaging) damage_reason += " '" + name + "'";
  }
  plan.push_back({"damage", !damaging.empty(), damage_reason});
  const std::size_t bodies = problem.body_names.size();
  std::string partition_reason;
  if (problem.contact.partitioning == Partitioning::bodies)
    partition_reason = "partitioning = \"bodies\" in [contact]: body 0 and the other bodies are "
                       "two always-separable fields (multimaterial contact, 004 §2.2)";
  else if (problem.contact.partitioning == Partitioning::off)
    partition_reason = "partitioning = \"off\" in [contact]: one velocity field (single-field MPM)";
  else if (partitioning_active(problem))
    partition_reason =
        "damage-field-gradient partitioning with two fields per node (" +
        (bodies > 1 ? std::to_string(bodies) + " bodies, surface flags make them separable"
                    : std::string("damage can open cracks")) +
        "); kernel neighbour search radius = cell diagonal";
  else
    partition_reason = "one body and no damage: one velocity field, no neighbour search";
  plan.push_back({"partitioning", partitioning_active(problem), partition_reason});
  plan.push_back({"thermal", problem.thermal.active(),
                  problem.thermal.active() ? problem.thermal.reason
                                           : "no thermal data and no heat sources: no thermal arrays"});
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
  // The explicit conduction limit joins the CFL limit when the thermal module runs (DESIGN §4).
  const double thermal_limit = thermal_stable_time_step<D>(problem, particles, cfl);
  if (max_speed <= 0.0) return thermal_limit;
  // Multilinear hats with a lumped mass: the stiffest grid mode of a cell has ω = 2c√D/h, so
  // central-difference stepping is stable for Δt < 2/ω = h/(c√D). The DESIGN's h/c is the 1D value
  // and lets a 2D scene run unstably at C_cfl close to 1.
  return std::min(thermal_limit, cfl * problem.grid.cell_size / (std::sqrt(double(D)) * max_speed));
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
  double kernel_radius = 0.0;  ///< r_p of the damage field = cell diagonal (001 §2.2) [m]

  GridIndex<D> grid;
  /// Per node and field (field 1 exists only with partitioning): mass, momentum, force, and the
  /// velocities before (lumped) and after the grid update.
  std::array<std::vector<double>, 2> node_mass;
  std::array<std::vector<Vec<D>>, 2> node_momentum, node_force, node_velocity_lumped, node_velocity;
  // Race-free, thread-count-independent scatter: particles are binned into strips along direction 0
  // that are wider than twice any stencil's reach, so strips of equal parity never share a node.
  // Even strips scatter in parallel, then odd ones; within a strip particles go in index order, so
  // every node sums its contributions in the same order whatever the number of threads.
  std::int64_t strip_width = 3;         ///< cells per strip
  double largest_half_extent = 0.0;     ///< largest stencil half-extent along direction 0 [cells]
  std::vector<std::int64_t> strip_start, strip_order, strip_of, strip_cursor;
  int thread_slots = 1;
  IVec<D> domain_nodes;  ///< number of cells of the computational domain per direction

  // ---- damage
  bool damage_on = false;
  std::vector<char> material_damages;

  // ---- partitioning (001 §2.1-2.3, Alg. 1-3); arrays exist only when `partitioned`
  bool partitioned = false;
  bool partition_this_step = false;    ///< some particle has d̂ > 0
  bool by_bodies = false;              ///< fields are the two bodies, always separable
  NeighbourLists<D> neighbours;
  std::vector<double> particle_dhat, particle_field;  ///< d̂_p = max(s_p, d_p), D̄(x_p)
  std::vector<Vec<D>> particle_gradient;              ///< ∇D̄(x_p) (001 eq. 17-19)
  std::vector<Vec<D>> node_gradient;                  ///< nonlocal nodal ∇D̄_i (001 §2.2, Alg. 1)
  std::vector<Mat<D>> node_gradient_tensor;           ///< Σ_p ∇D̄_p ⊗ ∇D̄_p (principal rule only)
  std::array<std::vector<Vec<D>>, 2> node_mass_gradient;  ///< Σ m_p ∇S̄_ip per field (000 eq. 74)
  std::array<std::vector<double>, 2> node_dhat;           ///< Σ S̄ m_p d̂_p per field (000 eq. 70)
  std::array<std::vector<Vec<D>>, 2> node_volume_gradient;  ///< Σ V_p ∇S̄_ip per field (contact area)
  bool needs_contact_area = false;  ///< the contact friction law has a strength term (004 eq. 24)
  std::array<std::vector<Vec<D>>, 2> node_position;       ///< Σ S̄ m_p x_p per field (004 eq. 8)
  std::vector<double> node_dhat_max;                      ///< largest d̂ mapping to the node
  /// Pre-pass of 001 Alg. 2 (nodal_damage_gradient), for the junction rule of field_of: the
  /// largest damage d (not d̂: surface flags excluded) mapping to the node, and per field f the
  /// sums Σ S̄ d̂_p x_p, Σ S̄ d̂_p over the particles whose gradient decides their field f at the
  /// node: their ratio c_f is the centre of field f's side of the band.
  std::vector<double> node_damage_max;
  std::array<std::vector<Vec<D>>, 2> node_side_moment;
  std::array<std::vector<double>, 2> node_side_weight;
  std::vector<std::int64_t> two_field_nodes;
  std::vector<double> node_friction_work;
  std::vector<double> node_normal_impulse, node_contact_area;  ///< per two-field node, for contact heat
  long long contact_nodes_last_step = 0;

  // ---- traction loads
  std::vector<Vec<D>> load_force;  ///< f_p of this step [N per unit thickness in 2D]

  // ---- thermal module (thermal_step.hpp); exists only when the scene needs it
  std::unique_ptr<ThermalModule<D>> thermal;

  explicit Impl(Problem<D> p) : problem(std::move(p)) {
    for (const auto& m : problem.materials) {
      models.push_back({m.bulk_modulus, m.shear_modulus});
      material_damages.push_back(m.damages() ? 1 : 0);
      if (m.damages()) damage_on = true;
    }
    partitioned = partitioning_active(problem);
    by_bodies = problem.contact.partitioning == Partitioning::bodies;
    // Adhesion (004 eq. 24) and contact conductance (000 eq. 12-13) scale with the contact area.
    needs_contact_area =
        std::holds_alternative<AdhesiveFriction>(problem.contact.friction) || problem.thermal.active();
    kernel_radius = problem.grid.cell_size * std::sqrt(double(D));
    grid.origin = problem.grid.min;
    grid.cell_size = problem.grid.cell_size;
    grid.inverse_cell_size = 1.0 / problem.grid.cell_size;
    for (int k = 0; k < D; ++k)
      domain_nodes[k] = static_cast<std::int64_t>(
          std::llround((problem.grid.max[k] - problem.grid.min[k]) / problem.grid.cell_size));
    double lightest = std::numeric_limits<double>::infinity();
    for (double m : problem.particles.mass) lightest = std::min(lightest, m);
    negligible_mass = std::isfinite(lightest) ? negligible_node_mass_fraction * lightest : 0.0;
    if (!problem.loads.empty()) load_force.assign(problem.particles.size(), Vec<D>::Zero());
    if (problem.thermal.active()) thermal = std::make_unique<ThermalModule<D>>(problem);
    compute_stress_and_energy_of_initial_state();
  }

  /// Whether the two fields of node i (both holding mass) may separate: 001 §2.3, Alg. 3;
  /// 000 eq. 70-71 on d̂ = max(s, d). Valid after particles_to_grid<…, true>.
  bool node_separable(std::size_t i) const {
    if (by_bodies) return true;
    return node_dhat_max[i] >= problem.contact.critical_damage &&
           std::min(node_dhat[0][i] / node_mass[0][i], node_dhat[1][i] / node_mass[1][i]) >
               problem.contact.minimum_damage;
  }

  /// Stress, stored energy and damage bookkeeping of one particle from its F and damage: the
  /// trial stress σ^E is degraded by d (001 eq. 26-27 or 000 eq. 7) and the stored energy is
  /// ψ(F) − d ψ_t, ψ_t being the part of ψ that the degradation acts on.
  double stress_and_stored_energy(std::int64_t p) {
    auto& P = problem.particles;
    const NeoHookean& model = models[P.material[p]];
    Mat<D> trial = model.cauchy<D>(P.F[p]);
    if (thermal) trial += thermal->stress(P.material[p], P.F[p], P.temperature[p]);
    const double psi = model.energy_density<D>(P.F[p]);
    const double d = P.damage[p];
    if (d <= 0.0) {
      P.stress[p] = trial;
      return psi;
    }
    const MaterialSpec& spec = problem.materials[P.material[p]];
    P.stress[p] = degrade_stress<D>(trial, d, spec.degradation);
    return psi - d * std::clamp(degradable_energy<D>(model, P.F[p], spec.degradation), 0.0, psi);
  }

  void compute_stress_and_energy_of_initial_state() {
    auto& P = problem.particles;
    double kinetic = 0.0, strain = 0.0;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
#pragma omp parallel for reduction(+ : kinetic, strain) schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      strain += P.volume0[p] * stress_and_stored_energy(p);
      kinetic += 0.5 * P.mass[p] * P.v[p].squaredNorm();
    }
    totals = EnergyAccumulators{};
    totals.initial_energy = kinetic + strain;
    row = SeriesRow<D>{};
    row.kinetic = kinetic;
    row.strain = strain;
    row.thermal = thermal_energy<D>(problem, P);
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
    const int fields = partition_this_step ? 2 : 1;
    for (int f = 0; f < fields; ++f) {
      node_mass[f].assign(nodes, 0.0);
      node_momentum[f].assign(nodes, Vec<D>::Zero());
      node_force[f].assign(nodes, Vec<D>::Zero());
      node_velocity_lumped[f].resize(nodes);
      node_velocity[f].resize(nodes);
    }
    if (partition_this_step) {
      node_gradient.assign(nodes, Vec<D>::Zero());
      if (!by_bodies && problem.contact.nodal_gradient == NodalGradientRule::principal)
        node_gradient_tensor.assign(nodes, Mat<D>::Zero());
      node_dhat_max.assign(nodes, 0.0);
      if (!by_bodies) {
        node_damage_max.assign(nodes, 0.0);
        for (int f = 0; f < 2; ++f) {
          node_side_moment[f].assign(nodes, Vec<D>::Zero());
          node_side_weight[f].assign(nodes, 0.0);
        }
      }
      for (int f = 0; f < 2; ++f) {
        node_mass_gradient[f].assign(nodes, Vec<D>::Zero());
        node_dhat[f].assign(nodes, 0.0);
        if (problem.contact.position_gap_test) node_position[f].assign(nodes, Vec<D>::Zero());
        if (needs_contact_area) node_volume_gradient[f].assign(nodes, Vec<D>::Zero());
      }
    }
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
    strip_cursor.assign(strip_start.begin(), strip_start.end() - 1);
    for (std::int64_t p = 0; p < n; ++p) strip_order[strip_cursor[strip_of[p]]++] = p;
  }

  /// Runs body(p, stencil) over all particles, strip by strip in two parity passes, so that bodies
  /// that scatter into the stencil's nodes never race and sum in a thread-independent order.
  template <ShapeFunctionKind Kind, class Body>
  void for_each_particle_scatter(Body&& body) {
    for_each_particle_scatter_where<Kind>([](std::int64_t) { return true; }, body);
  }

  /// The same over the particles p with keep(p) only: no stencil is built for the others.
  template <ShapeFunctionKind Kind, typename Keep, typename Body>
  void for_each_particle_scatter_where(Keep&& keep, Body&& body) {
    const std::int64_t strips = static_cast<std::int64_t>(strip_start.size()) - 1;
    for (std::int64_t parity = 0; parity < 2; ++parity) {
#pragma omp parallel
      {
        Stencil<D> s;
#pragma omp for schedule(dynamic, 1)
        for (std::int64_t strip = parity; strip < strips; strip += 2) {
          for (std::int64_t k = strip_start[strip]; k < strip_start[strip + 1]; ++k) {
            const std::int64_t p = strip_order[k];
            if (!keep(p)) continue;
            fill_stencil<Kind>(problem.particles, p, grid, s);
            body(p, s);
          }
        }
      }
    }
  }

  template <ShapeFunctionKind Kind>
  static void fill_stencil(const Particles<D>& P, std::int64_t p, const GridIndex<D>& g,
                           Stencil<D>& s) {
    if constexpr (Kind == ShapeFunctionKind::linear) linear_stencil<D>(P.x[p], g, s);
    else if constexpr (Kind == ShapeFunctionKind::ugimp)
      ugimp_stencil<D>(P.x[p], 0.5 * P.domain[p].diagonal().cwiseAbs(), g, s);
    else cpdi_stencil<D>(P.x[p], P.domain[p], g, s);
  }

  /// d̂_p = max(s_p, d_p) and the kernel damage field with its gradient at every particle
  /// (001 eq. 17-19, §2.4; 000 eq. 67). Skipped while every d̂ is zero: then no node can have
  /// two fields.
  void update_damage_field() {
    const auto& P = problem.particles;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    particle_dhat.resize(P.size());
    bool any = false;
#pragma omp parallel for reduction(|| : any) schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      particle_dhat[p] = std::max(static_cast<double>(P.surface[p]), P.damage[p]);
      any = any || particle_dhat[p] > 0.0;
    }
    partition_this_step = any;
    if (!any) return;
    neighbours.update(P.x, kernel_radius, problem.contact.rebuild_fraction);
    damage_field_gradient<D>(neighbours, P.x, particle_dhat, kernel_radius, particle_field,
                             particle_gradient);
  }

  /// The nonlocal nodal damage-field gradient (001 §2.2). Default: the principal direction of
  /// Σ_p ∇D̄_p ⊗ ∇D̄_p over the particles mapping to the node, the n maximising Σ_p (n·∇D̄_p)², so
  /// the opposite gradients on the two faces of a crack reinforce. Alternative: 001 Alg. 1, the
  /// particle gradient of largest norm (total-order tie-break: independent of the scatter order).
  template <ShapeFunctionKind Kind>
  void nodal_damage_gradient() {
    const auto& P = problem.particles;
    auto add_damage = [&](std::int64_t p, const Stencil<D>& s) {
      if (P.damage[p] <= 0.0) return;
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        node_damage_max[i] = std::max(node_damage_max[i], P.damage[p]);
      }
    };
    // Only damaged particles and those within reach of damage or a surface (a gradient) take
    // part; the others (most of a body's interior) need no stencil here.
    const auto takes_part = [&](std::int64_t p) {
      return P.damage[p] > 0.0 || particle_gradient[p].squaredNorm() > 0.0;
    };
    if (problem.contact.nodal_gradient == NodalGradientRule::largest) {
      for_each_particle_scatter_where<Kind>(takes_part, [&](std::int64_t p, const Stencil<D>& s) {
        add_damage(p, s);
        const Vec<D>& g = particle_gradient[p];
        if (g.squaredNorm() <= 0.0) return;
        for (int e = 0; e < s.count; ++e)
          fold_nodal_gradient<D>(g, node_gradient[static_cast<std::size_t>(s.node[e])]);
      });
      band_sides<Kind>();
      return;
    }
    for_each_particle_scatter_where<Kind>(takes_part, [&](std::int64_t p, const Stencil<D>& s) {
      add_damage(p, s);
      const Vec<D>& g = particle_gradient[p];
      if (g.squaredNorm() <= 0.0) return;
      for (int e = 0; e < s.count; ++e)
        if (s.weight[e] > 0.0)
          accumulate_gradient_tensor<D>(g, node_gradient_tensor[static_cast<std::size_t>(s.node[e])]);
    });
    const std::int64_t nodes = static_cast<std::int64_t>(node_gradient.size());
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < nodes; ++i)
      if (node_gradient_tensor[i].squaredNorm() > 0.0)
        node_gradient[i] = principal_gradient<D>(node_gradient_tensor[i]);
    band_sides<Kind>();
  }

  /// The two sides of the d̂-band at each node (for the junction rule of field_of): Σ S̄ d̂_p x_p and Σ S̄ d̂_p per
  /// field over the band particles whose gradient decides their field there (Alg. 2's sign test).
  template <ShapeFunctionKind Kind>
  void band_sides() {
    auto in_band = [&](std::int64_t p) {
      return particle_dhat[p] > 0.0 && particle_gradient[p].squaredNorm() > 0.0;
    };
    for_each_particle_scatter_where<Kind>(in_band, [&](std::int64_t p, const Stencil<D>& s) {
      const double dhat = particle_dhat[p];
      const Vec<D>& g = particle_gradient[p];
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        if (s.weight[e] <= 0.0 || !gradient_decides_field<D>(g, node_gradient[i])) continue;
        const int f = particle_field_at_node<D>(g, node_gradient[i]);
        node_side_weight[f][i] += s.weight[e] * dhat;
        node_side_moment[f][i] += (s.weight[e] * dhat) * problem.particles.x[p];
      }
    });
  }

  /// Whether Alg. 2's sign test is meaningless for surface particle p at node i because p sits
  /// where pre-existing surfaces meet. 001 §2.4 makes touching bodies separable by flagging their
  /// boundary particles (d̂ = s = 1), so the kernel field D̄ is a band along every flagged face and
  /// ∇D̄_p points from p's side into the band (001 eq. 17-19). At a node of a contact surface whose
  /// band ends at a free face of one body (the billet corner under the overhanging platen, P2), the
  /// corner particle's ∇D̄_p points along the free face's normal — within a few degrees of the
  /// contact plane — and ∇D̄_p · ∇D̄_i (001 Alg. 2) is the noise of two almost perpendicular
  /// vectors: the corner joins the other body's field and is dragged with it. Such a particle is
  /// instead put on the side of the band it lies on, as Alg. 2 already does for particles with
  /// ∇D̄_p = 0: the band particles whose gradients do decide (|cos| ≥ ambiguous_gradient_cosine)
  /// give the two sides' centres c_0, c_1 (band_sides), and p joins the nearer one along c_1 − c_0
  /// — the local normal of the band, which at the corner is not tilted by the free face's flags as
  /// ∇D̄_i is (a one-sided band centre or the node position put the corner on the platen's side at
  /// nodes below the interface). It applies only to faces that exist before any damage: p's d̂ is
  /// its surface flag (s_p = 1, d_p < D_cr) and no particle with damage d ≥ D_min maps to the
  /// node. At a growing crack the tip particles' gradients are also almost in the crack plane, but
  /// there the sign test is what 001 §2.2-2.3 validate (applying the rule there stopped the V6
  /// notched-bar crack at 6 of 8 mm).
  bool junction_of_surfaces(std::int64_t p, std::size_t node, const Vec<D>& g, const Vec<D>& nodal) const {
    const auto& P = problem.particles;
    return P.surface[p] != 0 && P.damage[p] < problem.contact.critical_damage &&
           node_damage_max[node] < problem.contact.minimum_damage && node_side_weight[0][node] > 0.0 &&
           node_side_weight[1][node] > 0.0 &&
           !gradient_decides_field<D>(g, nodal) && nodal.squaredNorm() > 0.0;
  }

  /// 001 Alg. 2: field 0 when ∇D̄_p · ∇D̄_i ≥ 0, else field 1; a particle beyond the reach of any
  /// damage (∇D̄_p = 0) joins the side of the node it lies on instead of always field 0, and a
  /// surface particle at a junction of pre-existing surfaces the side of the band it lies on
  /// (junction_of_surfaces). With
  /// partitioning by bodies the field is the body id (two bodies, 004 §2.2 multimaterial contact).
  int field_of(std::int64_t p, std::size_t node) const {
    if (by_bodies) return problem.particles.body[p] == 0 ? 0 : 1;
    const Vec<D>& g = particle_gradient[p];
    const Vec<D>& nodal = node_gradient[node];
    if (g.squaredNorm() > 0.0) {
      if (!junction_of_surfaces(p, node, g, nodal)) return particle_field_at_node<D>(g, nodal);
      // The side of the band p lies on: nearer to c_0 or to c_1 along c_1 − c_0.
      const Vec<D> c0 = node_side_moment[0][node] / node_side_weight[0][node];
      const Vec<D> c1 = node_side_moment[1][node] / node_side_weight[1][node];
      return (problem.particles.x[p] - 0.5 * (c0 + c1)).dot(c1 - c0) <= 0.0 ? 0 : 1;
    }
    if (nodal.squaredNorm() == 0.0) return 0;  // a node away from any damage: one field
    // Only then the node's position (an index decomposition, costly in the scatter loops).
    const Vec<D> offset = problem.particles.x[p] - grid.position(grid.global(static_cast<std::int64_t>(node)));
    return particle_field_at_node<D>(g, nodal, offset);
  }

  /// 000 eq. (47)-(49): m_i = Σ S̄ m_p, p_i = Σ S̄ m_p v_p, f_i = Σ S̄ (m_p g + f_p) − Σ V_p σ_p ∇S̄,
  /// into the particle's field at each node when partitioned (001 Alg. 2).
  template <ShapeFunctionKind Kind, bool Partitioned>
  void particles_to_grid() {
    const auto& P = problem.particles;
    const Vec<D> gravity = problem.gravity;
    const bool loaded = !load_force.empty();
    const bool gap_test = problem.contact.position_gap_test;
    const bool area_needed = needs_contact_area;
    for_each_particle_scatter<Kind>([&](std::int64_t p, const Stencil<D>& s) {
      const double volume = P.volume0[p] * P.F[p].determinant();
      const Mat<D> volume_stress = volume * P.stress[p];
      const Vec<D> momentum = P.mass[p] * P.v[p];
      const Vec<D> external = P.mass[p] * gravity + (loaded ? load_force[p] : Vec<D>::Zero());
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        int f = 0;
        // A node without a nodal damage gradient keeps every particle in field 0 (field_of), so it
        // never has two fields and needs none of the contact sums below.
        bool contact_node = false;
        if constexpr (Partitioned) {
          contact_node = by_bodies || node_gradient[i].squaredNorm() > 0.0;
          if (contact_node) f = field_of(p, i);
        }
        node_mass[f][i] += s.weight[e] * P.mass[p];
        node_momentum[f][i] += s.weight[e] * momentum;
        node_force[f][i] += s.weight[e] * external - volume_stress * s.gradient[e];
        if (contact_node) {
          node_mass_gradient[f][i] += P.mass[p] * s.gradient[e];
          const double dhat = by_bodies ? 0.0 : particle_dhat[p];
          node_dhat[f][i] += s.weight[e] * P.mass[p] * dhat;
          if (s.weight[e] > 0.0) node_dhat_max[i] = std::max(node_dhat_max[i], dhat);
          if (gap_test) node_position[f][i] += s.weight[e] * P.mass[p] * P.x[p];
          if (area_needed) node_volume_gradient[f][i] += volume * s.gradient[e];
        }
      }
    });
  }

  void update_grid_velocities(double dt) {
    const std::int64_t nodes = static_cast<std::int64_t>(node_mass[0].size());
    const int fields = partition_this_step ? 2 : 1;
    for (int f = 0; f < fields; ++f) {
      const auto& mass = node_mass[f];
      const auto& momentum = node_momentum[f];
      const auto& force = node_force[f];
      auto& lumped = node_velocity_lumped[f];
      auto& velocity = node_velocity[f];
#pragma omp parallel for schedule(static)
      for (std::int64_t i = 0; i < nodes; ++i) {
        if (mass[i] > negligible_mass) {
          lumped[i] = momentum[i] / mass[i];
          velocity[i] = lumped[i] + dt * force[i] / mass[i];
        } else {
          lumped[i].setZero();
          velocity[i].setZero();
        }
      }
    }
  }

  /// Two fields at a node either move as one (not separable: 001 Alg. 3 "treat as single field")
  /// or exchange momentum through the contact law (000 eq. 72-77; 004 §2.6). Nodes are processed
  /// independently; the friction work is summed serially in node order.
  void resolve_two_field_nodes(double dt) {
    const std::int64_t nodes = static_cast<std::int64_t>(node_mass[0].size());
    two_field_nodes.clear();
    for (std::int64_t i = 0; i < nodes; ++i)
      if (node_mass[1][i] > negligible_mass) two_field_nodes.push_back(i);
    const std::int64_t count = static_cast<std::int64_t>(two_field_nodes.size());
    node_friction_work.assign(two_field_nodes.size(), 0.0);
    if (thermal) {
      node_normal_impulse.assign(two_field_nodes.size(), 0.0);
      node_contact_area.assign(two_field_nodes.size(), 0.0);
    }
    const ContactSpec<D>& contact = problem.contact;
    const bool prescribed_normal = contact.normal.squaredNorm() > 0.0;
    const Vec<D> fixed_normal =
        prescribed_normal ? Vec<D>(contact.normal.normalized()) : Vec<D>::Zero();
    long long in_contact = 0;
#pragma omp parallel for reduction(+ : in_contact) schedule(static)
    for (std::int64_t k = 0; k < count; ++k) {
      const std::size_t i = static_cast<std::size_t>(two_field_nodes[k]);
      const double m0 = node_mass[0][i], m1 = node_mass[1][i];
      if (m0 <= negligible_mass) {  // everything mapped to field 1: it is the node's only field
        node_velocity[0][i] = node_velocity[1][i];
        node_velocity_lumped[0][i] = node_velocity_lumped[1][i];
        continue;
      }
      const bool separable = node_separable(i);
      // Normal from field 0 towards field 1: mass gradients point out of their field (000 eq. 74),
      // so n₀ = (g₀ − g₁)/|g₀ − g₁| and n₁ = −n₀ exactly (momentum-conserving pair).
      Vec<D> normal = node_mass_gradient[0][i] - node_mass_gradient[1][i];
      if (prescribed_normal) normal = normal.dot(fixed_normal) >= 0.0 ? fixed_normal : Vec<D>(-fixed_normal);
      const double normal_length = normal.norm();
      if (!separable || !(normal_length > 0.0)) {
        const double m = m0 + m1;
        const Vec<D> lumped = (node_momentum[0][i] + node_momentum[1][i]) / m;
        const Vec<D> velocity = (m0 * node_velocity[0][i] + m1 * node_velocity[1][i]) / m;
        for (int f = 0; f < 2; ++f) {
          node_velocity_lumped[f][i] = lumped;
          node_velocity[f][i] = velocity;
        }
        continue;
      }
      ContactNode<D> pair;
      pair.mass_a = m0;
      pair.mass_b = m1;
      pair.velocity_a = node_velocity[0][i];
      pair.velocity_b = node_velocity[1][i];
      pair.normal = normal / normal_length;
      // Tributary interface area from the fields' volume gradients (divergence theorem; exact also
      // where an interface ends inside the node's support, where 004 eq. 11 over-estimates: at the
      // edge of the sliding block it gives 0.61 h instead of h/2, 5 % too much adhesion at 5 mm).
      pair.area = needs_contact_area ? contact_area_from_gradients<D>(node_volume_gradient[0][i],
                                                                       node_volume_gradient[1][i], pair.normal)
                                     : 0.0;
      if (contact.position_gap_test) {
        // 004 eq. (8) with the normal pointing from a to b: the surfaces overlap when the field
        // centres are closer along n than 0.8 h (the printed (x_a − x_b)·n has the opposite sign
        // to the stated normal direction).
        const Vec<D> centre0 = node_position[0][i] / m0, centre1 = node_position[1][i] / m1;
        pair.gap_closed = (centre1 - centre0).dot(pair.normal) - 0.8 * grid.cell_size < 0.0;
      }
      if (thermal) pair.temperature = thermal->interface_temperature(i);  // 000 eq. 15, Alg. 3 line 12
      pair.force_a = node_force[0][i];
      pair.force_b = node_force[1][i];
      const ContactExchange<D> exchange =
          exchange_momentum<D>(pair, contact.friction, dt, contact.friction_work_order);
      if (!exchange.in_contact) continue;
      ++in_contact;
      if (thermal) {
        node_normal_impulse[k] = exchange.normal_impulse;
        node_contact_area[k] = pair.area;
      }
      node_velocity[0][i] += exchange.momentum_change_a / m0;
      node_velocity[1][i] -= exchange.momentum_change_a / m1;
      node_friction_work[k] = exchange.friction_work;
    }
    double friction = 0.0;
    for (double w : node_friction_work) friction += w;
    totals.friction_work += friction;
    contact_nodes_last_step = in_contact;
  }

  /// Rigid walls (004 §2.12: a field in contact with a wall takes the wall's velocity in the
  /// normal direction; the friction law limits the tangential change). Node impulses J give each
  /// wall's reaction force and the wall work Σ J·v_wall. Friction work comes from the same
  /// exchange as between two fields, with the wall as an infinitely heavy partner.
  void apply_walls(double dt) {
    const std::int64_t nodes = static_cast<std::int64_t>(node_mass[0].size());
    const double tolerance = 1e-9 * grid.cell_size;
    const int fields = partition_this_step ? 2 : 1;
    for (std::size_t w = 0; w < problem.walls.size(); ++w) {
      const WallSpec<D>& wall = problem.walls[w];
      const Vec<D> wall_velocity = wall.velocity.velocity(time + dt);
      const Vec<D> wall_shift = wall.velocity.displacement(time + dt);
      // A bilateral wall (fixed, roller) holds the nodes it touches: when it moves away from the
      // material it pulls them along instead of letting go, so its plane test keeps the start plane
      // until the wall advances into the material. Without this, a driven edge whose wall retracts
      // (the trailing driver of V7, 004 §3: edges "moved by rigid blocks") was released at once and
      // its Poisson pre-stress came free as a 70 J/m kinetic-energy burst. A contact wall is one-sided
      // and always tests its current plane. (Limitation: a bilateral wall that advances and then
      // retracts releases the nodes it took beyond its start plane.)
      const double advance = wall_shift.dot(wall.normal);
      const bool holds = wall.kind != WallKind::contact && advance < 0.0;
      const Vec<D> held_shift = wall_shift - (holds ? advance : 0.0) * wall.normal;
      const Vec<D> wall_point = wall.point + held_shift;
      Vec<D> impulse_sum = Vec<D>::Zero();
      double work = 0.0, friction = 0.0;
      // Serial and in node order: few nodes pass the plane test, and the sums must not depend on
      // the thread count.
      for (std::int64_t i = 0; i < nodes; ++i) {
        const Vec<D> node_point = grid.position(grid.global(i));
        if ((node_point - wall_point).dot(wall.normal) > tolerance) continue;
        if (!wall.region.contains(node_point, held_shift, tolerance)) continue;
        for (int f = 0; f < fields; ++f) {
          const double m = node_mass[f][i];
          if (m <= negligible_mass) continue;
          Vec<D>& velocity = node_velocity[f][i];
          const Vec<D> relative = velocity - wall_velocity;
          const double approach = relative.dot(wall.normal);
          Vec<D> change = Vec<D>::Zero();
          switch (wall.kind) {
            case WallKind::fixed: change = -relative; break;
            case WallKind::roller: change = -approach * wall.normal; break;
            case WallKind::contact: {
              ContactNode<D> pair;
              pair.mass_a = m;
              pair.mass_b = std::numeric_limits<double>::infinity();
              pair.velocity_a = velocity;
              pair.velocity_b = wall_velocity;
              pair.normal = -wall.normal;  // from the material towards the wall
              pair.area = 0.0;
              pair.force_a = node_force[f][i];
              if (thermal) pair.temperature = thermal->node_temperature(f, static_cast<std::size_t>(i));
              const ContactExchange<D> exchange =
                  exchange_momentum<D>(pair, wall.friction, dt, problem.contact.friction_work_order);
              if (!exchange.in_contact) continue;
              change = exchange.momentum_change_a / m;
              friction += exchange.friction_work;
              if (thermal) thermal->add_wall_friction_heat(f, static_cast<std::size_t>(i), exchange.friction_work);
              break;
            }
          }
          velocity += change;
          impulse_sum += m * change;
          work += m * change.dot(wall_velocity);
        }
      }
      row.wall_force[w] = -impulse_sum / dt;  // force of the material on the wall
      totals.wall_work += work;
      totals.friction_work += friction;
    }
  }

  /// Failed particles keep their CPDI domain within one cell: the longest diagonal is scaled down
  /// to h (001 §2.6), so a fully damaged particle cannot smear across the crack it opened.
  void limit_failed_domain(Mat<D>& domain) const {
    double longest2 = 0.0;
    for (int signs = 0; signs < (1 << (D - 1)); ++signs) {
      Vec<D> diagonal = domain.col(0);
      for (int k = 1; k < D; ++k) diagonal += ((signs >> (k - 1)) & 1 ? -1.0 : 1.0) * domain.col(k);
      longest2 = std::max(longest2, diagonal.squaredNorm());
    }
    const double limit2 = grid.cell_size * grid.cell_size;
    if (longest2 > limit2) domain *= std::sqrt(limit2 / longest2);
  }

  /// G2P (000 eq. 64-66) and the stress update that closes the step (update-stress-last), with the
  /// damage law evaluated on the trial stress.
  template <ShapeFunctionKind Kind, bool Partitioned, bool Thermal>
  std::optional<NumericalFailure> grid_to_particles(double dt) {
    auto& P = problem.particles;
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    const double pic = problem.time.pic_fraction;
    const bool deform_domain = Kind == ShapeFunctionKind::cpdi;
    const Vec<D> gravity = problem.gravity;
    const bool loaded = !load_force.empty();
    double kinetic = 0.0, strain = 0.0, gravity_work = 0.0, load_work = 0.0, dissipated = 0.0,
           max_speed = 0.0;
    std::int64_t failed = -1;
    std::vector<double> momentum_parts(static_cast<std::size_t>(D) * thread_slots, 0.0);
#pragma omp parallel reduction(+ : kinetic, strain, gravity_work, load_work, dissipated) \
    reduction(max : max_speed)
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
          int f = 0;
          if constexpr (Partitioned) f = field_of(p, i);
          const Vec<D>& velocity = node_velocity[f][i];
          v_pic += s.weight[e] * velocity;
          v_change += s.weight[e] * (velocity - node_velocity_lumped[f][i]);
          velocity_gradient += velocity * s.gradient[e].transpose();
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
        const int material = P.material[p];
        const NeoHookean& model = models[material];
        Mat<D> trial = model.cauchy<D>(P.F[p]);
        if constexpr (Thermal) trial += thermal->stress(material, P.F[p], P.temperature[p]);  // 000 eq. 3
        if (material_damages[material]) {
          const MaterialSpec& spec = problem.materials[material];
          const double damage_before = P.damage[p];
          // l_ch = particle size: the width of the one-particle band a crack localises in
          // (see rankine_softening_modulus for why not the paper's cell diagonal).
          const double band_width =
              spec.characteristic_length > 0.0 ? spec.characteristic_length
                                               : (D == 2 ? std::sqrt(P.volume0[p]) : std::cbrt(P.volume0[p]));
          update_damage<D>(spec.damage, trial, P.strength[p], band_width, dt,
                           P.damage_history[p], P.damage[p]);
          const double psi = model.energy_density<D>(P.F[p]);
          if (P.damage[p] > 0.0) {
            // ½ Σ τᵢ ln λᵢ is the exact released energy only at small strain; at large stretch it
            // can exceed ψ itself, so it is bounded by ψ: damage never stores negative energy.
            const double degradable =
                std::clamp(degradable_energy<D>(model, P.F[p], spec.degradation), 0.0, psi);
            // Energy released at fixed deformation by the damage increment (secant dissipation).
            dissipated += P.volume0[p] * (P.damage[p] - damage_before) * degradable;
            strain += P.volume0[p] * (psi - P.damage[p] * degradable);
            P.stress[p] = degrade_stress<D>(trial, P.damage[p], spec.degradation);
            if (deform_domain && P.damage[p] >= 1.0) limit_failed_domain(P.domain[p]);
          } else {
            strain += P.volume0[p] * psi;
            P.stress[p] = trial;
          }
        } else {
          P.stress[p] = trial;
          strain += P.volume0[p] * model.energy_density<D>(P.F[p]);
        }
        kinetic += 0.5 * P.mass[p] * P.v[p].squaredNorm();
        gravity_work += P.mass[p] * gravity.dot(displacement);
        if (loaded) load_work += load_force[p].dot(displacement);
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
                     problem.materials[P.material[failed]].name + "', damage " +
                     std::to_string(P.damage[failed]) +
                     ") became inverted or non-finite: J = " +
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
    totals.load_work += load_work;
    totals.dissipated += dissipated;

    next_dt_limit = max_speed > 0.0
                        ? problem.time.cfl * grid.cell_size / (std::sqrt(double(D)) * max_speed)
                        : std::numeric_limits<double>::infinity();
    return std::nullopt;
  }

  void update_load_forces() {
    for (auto& f : load_force) f.setZero();
    for (const TractionLoad<D>& load : problem.loads) {
      const Vec<D> traction = load.traction(time);
      for (std::size_t k = 0; k < load.particles.size(); ++k)
        load_force[static_cast<std::size_t>(load.particles[k])] += load.boundary_measure[k] * traction;
    }
  }

  template <ShapeFunctionKind Kind, bool Thermal>
  std::optional<NumericalFailure> advance(double dt) {
    if (partition_this_step) {
      if (!by_bodies) nodal_damage_gradient<Kind>();
      particles_to_grid<Kind, true>();
      if constexpr (Thermal) thermal->template begin<Kind, true>(*this);  // nodal θⁿ for friction
      update_grid_velocities(dt);
      resolve_two_field_nodes(dt);
      if (!problem.walls.empty()) apply_walls(dt);
      if constexpr (Thermal) thermal->template finish<Kind, true>(*this, dt);  // 000 Alg. 1 line 5
      return grid_to_particles<Kind, true, Thermal>(dt);
    }
    particles_to_grid<Kind, false>();
    if constexpr (Thermal) thermal->template begin<Kind, false>(*this);
    update_grid_velocities(dt);
    if (!problem.walls.empty()) apply_walls(dt);
    if constexpr (Thermal) thermal->template finish<Kind, false>(*this, dt);
    return grid_to_particles<Kind, false, Thermal>(dt);
  }

  template <ShapeFunctionKind Kind>
  std::optional<NumericalFailure> advance_with_modules(double dt) {
    return thermal ? advance<Kind, true>(dt) : advance<Kind, false>(dt);
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
    partition_this_step = by_bodies;
    if (partitioned && !by_bodies) update_damage_field();
    resize_grid();
    bin_particles_into_strips();
    if (!load_force.empty()) update_load_forces();
    std::optional<NumericalFailure> failure;
    switch (problem.grid.shape_function) {
      case ShapeFunctionKind::linear: failure = advance_with_modules<ShapeFunctionKind::linear>(dt); break;
      case ShapeFunctionKind::ugimp: failure = advance_with_modules<ShapeFunctionKind::ugimp>(dt); break;
      case ShapeFunctionKind::cpdi: failure = advance_with_modules<ShapeFunctionKind::cpdi>(dt); break;
    }
    if (failure) return failure;
    if (thermal) {
      next_dt_limit = std::min(next_dt_limit, thermal->dt_limit());
      row.thermal = thermal_energy<D>(problem, problem.particles);
    }
    time += dt;
    ++step;
    row.step = step;
    row.time = time;
    row.dt = dt;
    row.totals = totals;
    row.balance_error = (row.kinetic + row.strain + totals.dissipated + totals.friction_work) -
                        (totals.initial_energy + totals.wall_work + totals.gravity_work +
                         totals.load_work);
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
  if (impl_->thermal) impl_->thermal = std::make_unique<ThermalModule<D>>(impl_->problem);
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
