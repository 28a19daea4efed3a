// The thermal stage of one step ([XLS21] Alg. 1-2), split around the mechanical grid update: its
// first half (thermal_begin) runs after the mechanical P2G and gives the nodal temperatures θⁿ that
// the contact friction law reads ([XLS21] eq. (15)); its second half (thermal_finish) runs after
// contact and walls and gives the particle temperatures θⁿ⁺¹, which the constitutive update at the
// end of the step uses. The P2G stresses were computed with θⁿ, so this is the staggered split of
// [XLS21] §3.4: θⁿ⁺¹ from the mechanical state n, then the mechanical state n+1 with θⁿ⁺¹.
//
// Derivation of the discrete heat equation ([XLS21] eq. (54)-(62); eq. (63) is garbled in our
// copy): [XLS21] eq. (43), ρ c θ̇ = −∇·q + ρ(D_int − H_in) − ρ H_e, times a test function w and
// integrated by parts over the current configuration:
//   ∫ w ρ c θ̇ dΩ = ∫ ∇w · q dΩ − ∮ w q·n dΓ + ∫ w ρ (D_int − H_in − H_e) dΩ.
// With θ = Σ_i S_i θ_i, w = S_i, a lumped capacity C_i = Σ_p m_p c_p S̄_ip (eq. (56)) and particle
// quadrature:
//   C_i θ̇_i = Σ_p V_p q_p · ∇S̄_ip + Q_i^ext + Q_i^cont + (sources),          (eq. (55), (57), (58),
//   (61))
// where −∮ w q·n dΓ is the boundary heat input Q_i^ext (flux q̄ or convection h(θ_∞ − θ) into the
// body). The particle flux is evaluated from the nodal temperature of this step instead of being
// carried as a state variable:
//   q_p = −κ_p Σ_i θ_i ∇S̄_ip,   θ_i = Σ_p m_p c_p θ_p S̄_ip / C_i   ([XLS21] eq. (18)),
// so θ_i is the capacity-weighted re-projection of the particle temperatures at the start of every
// step. The particles then take θ_p ← θ_p + Δt Σ_i S̄_ip θ̇_i (eq. (62)). Summed over p with weights
// m_p c_p this deposits exactly Σ_i C_i θ̇_i Δt, so the nodal heat loads are conserved.
//
// The local sources (elastic structural heating, eq. (39); damage heating, eq. (28), (40)) are
// applied at the particle that produces them rather than through the grid (eq. (59)-(60)): the
// round trip Σ_i S̄_ip S̄_iq / C_i only smears a particle's own heat over its neighbours, which makes
// an adiabatic (κ = 0) compress–release cycle irreversible. Their energy is unchanged.
#include <algorithm>
#include <cmath>

#include "step/nodes_behind_plane.hpp"
#include "step/particle_loops.hpp"
#include "step/partition.hpp"
#include "step/stages.hpp"

namespace fragmpm::mpm {

template <int D>
ThermalState<D>::ThermalState(const Problem<D>& problem) {
  const auto& P = problem.particles;
  const std::size_t n = P.size();
  last_J.resize(n);
  for (std::size_t p = 0; p < n; ++p) last_J[p] = P.F[p].determinant();
  last_damage = P.damage;
  for (std::size_t m = 0; m < problem.materials.size(); ++m) {
    const ThermalMaterial& t = problem.thermal.materials[m];
    bulk.push_back(problem.materials[m].bulk_modulus);
    expansion.push_back(t.expansion);
    reference.push_back(t.reference_temperature);
    conductivity.push_back(t.conductivity);
    specific_heat.push_back(t.specific_heat);
    degradation.push_back(problem.materials[m].degradation);
    damages.push_back(problem.materials[m].damages() ? 1 : 0);
  }
  set_negligible_capacity(P);
  for (const ThermalWallCondition<D>& c : problem.thermal.walls)
    if (c.kind == ThermalWallKind::flux || c.kind == ThermalWallKind::convection)
      boundary_measure = true;
  if (!problem.thermal.edge_loads.empty()) edge_source.assign(n, 0.0);
  for (const WallSpec<D>& w : problem.walls)
    if (w.kind == WallKind::contact) wall_friction = true;
  dt_limit = thermal_stable_time_step<D>(problem, P, problem.time.cfl);
}

template <int D>
void ThermalState<D>::set_negligible_capacity(const Particles<D>& P) {
  double lightest = std::numeric_limits<double>::infinity();
  for (std::size_t p = 0; p < P.size(); ++p)
    lightest =
        std::min(lightest, P.mass[p] * specific_heat[static_cast<std::size_t>(P.material[p])]);
  negligible_capacity = std::isfinite(lightest) ? 1e-10 * lightest : 0.0;
}

template <int D>
void ThermalState<D>::remove_particles(const Particles<D>& particles,
                                       const std::vector<std::size_t>& removed) {
  erase_entries(last_J, removed);
  erase_entries(last_damage, removed);
  erase_entries(edge_source, removed);
  set_negligible_capacity(particles);
}

namespace {

/// a_p q̄ or a_p h (θ_∞ − θ_p) per loaded particle [W per unit thickness in 2D].
template <int D>
void update_edge_sources(ThermalState<D>& T, const ThermalSpec<D>& spec, const Particles<D>& P) {
  std::fill(T.edge_source.begin(), T.edge_source.end(), 0.0);
  for (const HeatFluxLoad& load : spec.edge_loads)
    for (std::size_t k = 0; k < load.particles.size(); ++k) {
      const std::size_t p = static_cast<std::size_t>(load.particles[k]);
      const double q = load.kind == ThermalWallKind::convection
                           ? load.film_coefficient * (load.temperature - P.temperature[p])
                           : load.flux;
      T.edge_source[p] += load.boundary_measure[k] * q;
    }
}

/// Walls: prescribed temperature at the nodes on or behind the plane (Γ_θ); flux and convection on
/// the material face near the plane (Γ_q, Γ_h), with the face measure at node i from the divergence
/// theorem, ∫_Ω ∇S̄_i dV = ∮ S̄_i n dΓ: −n_wall · Σ_p V_p ∇S̄_ip is ∫ S̄_i dΓ over the face that looks
/// at the wall (the idea of [NBS18] eq. (6) applied to a wall). Nodes up to two cells in front of
/// the plane count, so a face between node rows is covered.
template <int D>
void apply_wall_loads(StepState<D>& state, int fields) {
  ThermalState<D>& T = *state.thermal;
  T.fixed_nodes.clear();
  const double h = state.grid.cell_size;
  const double tolerance = 1e-9 * h;
  for (const ThermalWallCondition<D>& c : state.problem.thermal.walls) {
    if (c.kind == ThermalWallKind::insulated) continue;
    const Vec<D> shift = c.velocity.displacement(state.time);
    const Vec<D> point = c.point + shift;
    for_each_node_behind_plane<D>(
        state.grid, point, c.normal, 2.0 * h, [&](std::int64_t node, const Vec<D>& x) {
          if (!c.region.contains(x, shift, tolerance)) return;
          const std::size_t i = static_cast<std::size_t>(node);
          const double distance = (x - point).dot(c.normal);
          for (int f = 0; f < fields; ++f) {
            if (!(T.capacity[f][i] > T.negligible_capacity)) continue;
            if (c.kind == ThermalWallKind::temperature) {
              if (distance <= tolerance) T.fixed_nodes.push_back({i, f, c.temperature});
              continue;
            }
            const double measure = std::max(0.0, -T.domain_gradient[f][i].dot(c.normal));
            const double q = c.kind == ThermalWallKind::flux
                                 ? c.flux
                                 : c.film_coefficient * (c.temperature - T.temperature[f][i]);
            T.load[f][i] += measure * q;
          }
        });
  }
}

/// Conductance of a separable contact node in contact this step, h_c A_c [W/K per unit thickness]
/// ([XLS21] eq. (12)-(13), (82)): h_c = h₀ |p/p₀|^ε with the contact pressure p = f_n / A_c from
/// this step's normal contact impulse (f_n = impulse/Δt) and area A_c; for ε = 1 this is γ̄ |f_n| of
/// eq. (82) and needs no area. 0 when the node is not in contact or nothing conducts.
template <int D>
double contact_conductance(const StepState<D>& state, std::size_t k, double dt) {
  const ThermalSpec<D>& spec = state.problem.thermal;
  const double impulse = state.contact.normal_impulse[k];
  if (!(spec.contact_conductance > 0.0) || !(impulse > 0.0)) return 0.0;
  const double force = impulse / dt;
  if (spec.contact_exponent == 1.0) return spec.contact_conductance / spec.contact_pressure * force;
  const double area = state.contact.area[k];
  if (!(area > 0.0)) return 0.0;
  return spec.contact_conductance *
         std::pow(force / (area * spec.contact_pressure), spec.contact_exponent) * area;
}

/// A contact whose conductance would equalise the two nodal temperatures within one step
/// (h_c A_c Δt ≥ C₀C₁/(C₀+C₁)) is thermally perfect: its fields share one temperature and one rate,
/// as non-separable fields do. Exchanging the capped flow explicitly instead would leave a
/// numerical resistance Δt(1/C₀ + 1/C₁) at the node.
template <int D>
void merge_perfect_contacts(StepState<D>& state, double dt) {
  ThermalState<D>& T = *state.thermal;
  reset_array(T.merged, T.capacity[0].size(), char{0});
  const auto& two_field = state.contact.two_field_nodes;
  for (std::size_t k = 0; k < two_field.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(two_field[k]);
    const double c0 = T.capacity[0][i], c1 = T.capacity[1][i];
    if (!(c0 > T.negligible_capacity && c1 > T.negligible_capacity) || !node_separable(state, i))
      continue;
    if (contact_conductance(state, k, dt) * dt < c0 * c1 / (c0 + c1)) continue;
    T.merged[i] = 1;
    const double theta = (T.heat[0][i] + T.heat[1][i]) / (c0 + c1);
    T.temperature[0][i] = T.temperature[1][i] = theta;
  }
}

/// Heat exchanged at separable two-field nodes in contact this step ([XLS21] eq. (11)-(14),
/// (79)-(82)): Q₀ = h_c A_c (θ₁ − θ₀) = −Q₁, capped so the explicit flow never overshoots, and the
/// friction work W of the step as heat W/Δt, half into each side (eq. (14), (82)).
template <int D>
void add_contact_heat(StepState<D>& state, double dt) {
  ThermalState<D>& T = *state.thermal;
  const bool conducts = state.problem.thermal.contact_conductance > 0.0;
  const auto& two_field = state.contact.two_field_nodes;
  for (std::size_t k = 0; k < two_field.size(); ++k) {
    const std::size_t i = static_cast<std::size_t>(two_field[k]);
    const double c0 = T.capacity[0][i], c1 = T.capacity[1][i];
    if (!(c0 > T.negligible_capacity && c1 > T.negligible_capacity) || !node_separable(state, i))
      continue;
    const double friction_heat = state.contact.friction_work[k] / dt;
    T.load[0][i] += 0.5 * friction_heat;
    T.load[1][i] += 0.5 * friction_heat;
    if (!conducts || T.merged[i]) continue;
    const double conductance_area = contact_conductance(state, k, dt);
    if (!(conductance_area > 0.0)) continue;
    const double jump = T.temperature[1][i] - T.temperature[0][i];
    const double equalising = c0 * c1 / (c0 + c1) / dt;
    const double flow = std::min(conductance_area, equalising) * jump;  // into field 0 [W]
    T.load[0][i] += flow;
    T.load[1][i] -= flow;
  }
}

}  // namespace

template <int D, ShapeFunctionKind Kind, bool Partitioned>
void thermal_begin(StepState<D>& state) {
  ThermalState<D>& T = *state.thermal;
  const auto& P = state.problem.particles;
  const std::size_t nodes = state.node_count();
  constexpr int fields = Partitioned ? 2 : 1;
  for (int f = 0; f < fields; ++f) {
    reset_array(T.capacity[f], nodes, 0.0);
    reset_array(T.heat[f], nodes, 0.0);
    reset_array(T.load[f], nodes, 0.0);
    reset_array(T.temperature[f], nodes, 0.0);
    reset_array(T.rate[f], nodes, 0.0);
    if (T.wall_friction) reset_array(T.wall_heat[f], nodes, 0.0);
    if (T.boundary_measure) reset_array(T.domain_gradient[f], nodes, Vec<D>::Zero().eval());
  }
  if (T.fixed_nodes.capacity() < 2 * nodes) T.fixed_nodes.reserve(2 * nodes);

  // Capacity and re-projected temperature per field ([XLS21] eq. (56), (18)).
  scatter_particles<D, Kind>(state, [&](std::int64_t p, const Stencil<D>& s) {
    const double mc = P.mass[p] * T.specific_heat[static_cast<std::size_t>(P.material[p])];
    const double mct = mc * P.temperature[p];
    const double volume = T.boundary_measure ? P.volume0[p] * P.F[p].determinant() : 0.0;
    for (int e = 0; e < s.count; ++e) {
      const std::size_t i = static_cast<std::size_t>(s.node[e]);
      const int f = field_at<D, Partitioned>(state, p, e);
      T.capacity[f][i] += s.weight[e] * mc;
      T.heat[f][i] += s.weight[e] * mct;
      if (T.boundary_measure) T.domain_gradient[f][i] += volume * s.gradient[e];
    }
  });
  const std::int64_t count = static_cast<std::int64_t>(nodes);
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    for (int f = 0; f < fields; ++f)
      if (T.capacity[f][i] > T.negligible_capacity)
        T.temperature[f][i] = T.heat[f][i] / T.capacity[f][i];
    if constexpr (Partitioned) {
      // Fields that move as one (not separable) are one body thermally too: one temperature.
      if (T.capacity[0][i] > T.negligible_capacity && T.capacity[1][i] > T.negligible_capacity &&
          !node_separable(state, static_cast<std::size_t>(i))) {
        const double theta = (T.heat[0][i] + T.heat[1][i]) / (T.capacity[0][i] + T.capacity[1][i]);
        T.temperature[0][i] = T.temperature[1][i] = theta;
      }
    }
  }
}

namespace {

/// θ_p ← θ_p + Δt Σ_i S̄_ip θ̇_i ([XLS21] eq. (62)), blended with the PIC value when
/// thermal_pic_fraction > 0, then the local sources of the mechanical step that just ended
/// (eq. (39), (28), (40)); returns the particle's conduction limit [s].
template <int D, ShapeFunctionKind Kind, bool Partitioned>
double update_particle_temperatures(StepState<D>& state, double dt) {
  ThermalState<D>& T = *state.thermal;
  auto& P = state.problem.particles;
  const std::int64_t n = static_cast<std::int64_t>(P.size());
  const double h2 = state.grid.cell_size * state.grid.cell_size;
  const double courant = state.problem.time.cfl;
  const double pic = state.problem.time.thermal_pic_fraction;  // 0 = eq. (62) alone
  double limit = std::numeric_limits<double>::infinity();
#pragma omp parallel reduction(min : limit)
  {
    Stencil<D> s;
#pragma omp for schedule(static)
    for (std::int64_t p = 0; p < n; ++p) {
      fill_stencil<D, Kind>(P, p, state.grid, s);
      double change = 0.0, projected = 0.0;
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        const int f = field_at<D, Partitioned>(state, p, e);
        change += s.weight[e] * T.rate[f][i];
        // PIC part: Σ S̄ (θ_i + Δt θ̇_i), a convex combination of nodal temperatures.
        if (pic > 0.0) projected += s.weight[e] * (T.temperature[f][i] + dt * T.rate[f][i]);
      }
      const std::size_t m = static_cast<std::size_t>(P.material[p]);
      double theta = P.temperature[p] + dt * change;
      if (pic > 0.0) theta = (1.0 - pic) * theta + pic * projected;
      const double J = P.F[p].determinant();
      const double density0 = P.mass[p] / P.volume0[p];
      const double d = P.damage[p];
      // Elastic structural heating over last_J → J at fixed damage (eq. (39), integrated exactly).
      if (T.expansion[m] != 0.0 && J != T.last_J[p])
        theta *=
            adiabatic_temperature_ratio(T.bulk[m], T.expansion[m], density0, T.specific_heat[m],
                                        coupling_fraction(d, T.degradation[m], J), T.last_J[p], J);
      // Damage dissipation and coupling heat of the damage increment (eq. (28), (40)), from the ψ_t
      // the last constitutive update found at this F and d.
      if (T.damages[m] && d > T.last_damage[p]) {
        // The coupling energy is released only where damage degrades it (coupling_fraction).
        const double released = coupling_fraction(1.0, T.degradation[m], J) < 1.0 ? 1.0 : 0.0;
        theta += damage_heat_density(state.degradable[p], T.bulk[m], released * T.expansion[m],
                                     T.reference[m], J, d - T.last_damage[p]) /
                 (density0 * T.specific_heat[m]);
      }
      // The plastic work of crushed material's flow is heat (all of it: nothing stores cold work
      // in a cohesionless granular flow).
      if (!state.flow_heat.empty()) {
        theta += state.flow_heat[static_cast<std::size_t>(p)] / (density0 * T.specific_heat[m]);
        state.flow_heat[static_cast<std::size_t>(p)] = 0.0;
      }
      P.temperature[p] = theta;
      T.last_J[p] = J;
      T.last_damage[p] = d;
      if (T.conductivity[m] > 0.0)
        limit = std::min(limit, courant * density0 / J * T.specific_heat[m] * h2 /
                                    (2.0 * D * T.conductivity[m]));
    }
  }
  return limit;
}

}  // namespace

template <int D, ShapeFunctionKind Kind, bool Partitioned>
void thermal_finish(StepState<D>& state, double dt) {
  ThermalState<D>& T = *state.thermal;
  auto& P = state.problem.particles;
  const ThermalSpec<D>& spec = state.problem.thermal;
  const std::int64_t count = static_cast<std::int64_t>(T.capacity[0].size());
  constexpr int fields = Partitioned ? 2 : 1;
  if constexpr (Partitioned) merge_perfect_contacts(state, dt);

  // Conduction Q_i^int = Σ_p V_p q_p·∇S̄_ip with q_p = −κ_p ∇θ(x_p) ([XLS21] eq. (18), (58)), and
  // heat input through body edges carried by particles, Q_i += S̄_ip a_p q̄ (eq. (57)).
  const bool edges = !T.edge_source.empty();
  if (edges) update_edge_sources(T, spec, P);
  scatter_particles<D, Kind>(state, [&](std::int64_t p, const Stencil<D>& s) {
    Vec<D> gradient = Vec<D>::Zero();
    for (int e = 0; e < s.count; ++e)
      gradient += T.temperature[field_at<D, Partitioned>(state, p, e)]
                               [static_cast<std::size_t>(s.node[e])] *
                  s.gradient[e];
    const double volume = P.volume0[p] * P.F[p].determinant();
    const Vec<D> volume_flux =
        -(volume * T.conductivity[static_cast<std::size_t>(P.material[p])]) * gradient;
    const double source = edges ? T.edge_source[p] : 0.0;
    for (int e = 0; e < s.count; ++e)
      T.load[field_at<D, Partitioned>(state, p, e)][static_cast<std::size_t>(s.node[e])] +=
          volume_flux.dot(s.gradient[e]) + s.weight[e] * source;
  });

  // Thermal conditions on walls ([XLS21] eq. (44), (57)); heat across and from separable contacts.
  if (!spec.walls.empty()) apply_wall_loads(state, fields);
  if constexpr (Partitioned) add_contact_heat(state, dt);
  if (T.wall_friction)
    for (int f = 0; f < fields; ++f)
      for (std::int64_t i = 0; i < count; ++i) T.load[f][i] += T.wall_heat[f][i] / dt;

        // Nodal rates (eq. (55)); two fields that are not separable share one rate.
#pragma omp parallel for schedule(static)
  for (std::int64_t i = 0; i < count; ++i) {
    for (int f = 0; f < fields; ++f)
      if (T.capacity[f][i] > T.negligible_capacity) T.rate[f][i] = T.load[f][i] / T.capacity[f][i];
    if constexpr (Partitioned) {
      if (T.capacity[0][i] > T.negligible_capacity && T.capacity[1][i] > T.negligible_capacity &&
          (!node_separable(state, static_cast<std::size_t>(i)) ||
           T.merged[static_cast<std::size_t>(i)])) {
        const double shared = (T.load[0][i] + T.load[1][i]) / (T.capacity[0][i] + T.capacity[1][i]);
        T.rate[0][i] = T.rate[1][i] = shared;
      }
    }
  }
  // θ = θ̄ on Γ_θ: the rate that takes the node there in this step.
  for (const auto& [i, f, value] : T.fixed_nodes)
    T.rate[static_cast<std::size_t>(f)][i] =
        (value - T.temperature[static_cast<std::size_t>(f)][i]) / dt;

  T.dt_limit = update_particle_temperatures<D, Kind, Partitioned>(state, dt);
}

#define FRAGMPM_INSTANTIATE_KIND(D, K, PART)                                 \
  template void thermal_begin<D, ShapeFunctionKind::K, PART>(StepState<D>&); \
  template void thermal_finish<D, ShapeFunctionKind::K, PART>(StepState<D>&, double);
#define FRAGMPM_INSTANTIATE(D)                 \
  template struct ThermalState<D>;             \
  FRAGMPM_INSTANTIATE_KIND(D, linear, false)   \
  FRAGMPM_INSTANTIATE_KIND(D, linear, true)    \
  FRAGMPM_INSTANTIATE_KIND(D, ugimp, false)    \
  FRAGMPM_INSTANTIATE_KIND(D, ugimp, true)     \
  FRAGMPM_INSTANTIATE_KIND(D, cpdi, false)     \
  FRAGMPM_INSTANTIATE_KIND(D, cpdi, true)      \
  FRAGMPM_INSTANTIATE_KIND(D, bspline2, false) \
  FRAGMPM_INSTANTIATE_KIND(D, bspline2, true)
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE
#undef FRAGMPM_INSTANTIATE_KIND

}  // namespace fragmpm::mpm
