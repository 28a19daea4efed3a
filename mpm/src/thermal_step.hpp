#pragma once
// Private to solver.cpp: the thermal stage of one step (000 Alg. 1 line 5, Alg. 2), run after the
// mechanical P2G of the step and before the grid velocity update, so that the stress update at the
// end of the step and the friction law (000 eq. 15, Alg. 3 line 12) see the new temperatures. The
// P2G stresses were computed with θⁿ, so this ordering is the staggered split of 000 §3.4: θⁿ⁺¹ from
// the mechanical state n, then the mechanical state n+1 with θⁿ⁺¹.
//
// Derivation of the discrete heat equation (000 eq. 54-62; eq. 63 is garbled in the text):
// 000 eq. (43), ρ c θ̇ = −∇·q + ρ(D_int − H_in) − ρ H_e, times a test function w and integrated by
// parts over the current configuration:
//   ∫ w ρ c θ̇ dΩ = ∫ ∇w · q dΩ − ∮ w q·n dΓ + ∫ w ρ (D_int − H_in − H_e) dΩ.
// With θ = Σ_i S_i θ_i, w = S_i, a lumped capacity C_i = Σ_p m_p c_p S̄_ip (eq. 56) and particle
// quadrature:
//   C_i θ̇_i = Σ_p V_p q_p · ∇S̄_ip + Q_i^ext + Q_i^cont + (sources),           (eq. 55, 57, 58, 61)
// where −∮ w q·n dΓ is the boundary heat input Q_i^ext (flux q̄ or convection h(θ_∞ − θ) into the
// body). The particle flux is evaluated from the nodal temperature of this step instead of being
// carried as a state variable (the garbled eq. 63 updates q_p incrementally):
//   q_p = −κ_p Σ_i θ_i ∇S̄_ip,   θ_i = Σ_p m_p c_p θ_p S̄_ip / C_i   (000 eq. 18; Alg. 2 lines 19-21),
// so θ_i is the capacity-weighted re-projection of the particle temperatures at the start of every
// step. The particles then take θ_p ← θ_p + Δt Σ_i S̄_ip θ̇_i (eq. 62). Summed over p with weights
// m_p c_p this deposits exactly Σ_i C_i θ̇_i Δt, so the nodal heat loads are conserved.
//
// The local sources (elastic structural heating, eq. 39; damage heating, eq. 28, 40) are applied at
// the particle that produces them rather than through the grid (eq. 59-60): the round trip
// Σ_i S̄_ip S̄_iq / C_i only smears a particle's own heat over its neighbours, which makes an
// adiabatic (κ = 0) compress–release cycle irreversible. Their energy is unchanged.
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "fragmpm/mpm/grid_index.hpp"
#include "fragmpm/mpm/problem.hpp"
#include "fragmpm/mpm/shape_functions.hpp"
#include "fragmpm/mpm/thermal.hpp"

namespace fragmpm::mpm {

template <int D>
class ThermalModule {
 public:
  explicit ThermalModule(const Problem<D>& problem) {
    const auto& P = problem.particles;
    const std::size_t n = P.size();
    last_J_.resize(n);
    for (std::size_t p = 0; p < n; ++p) last_J_[p] = P.F[p].determinant();
    last_damage_ = P.damage;
    for (std::size_t m = 0; m < problem.materials.size(); ++m) {
      const ThermalMaterial& t = problem.thermal.materials[m];
      bulk_.push_back(problem.materials[m].bulk_modulus);
      expansion_.push_back(t.expansion);
      reference_.push_back(t.reference_temperature);
      conductivity_.push_back(t.conductivity);
      specific_heat_.push_back(t.specific_heat);
      degradation_.push_back(problem.materials[m].degradation);
      damages_.push_back(problem.materials[m].damages() ? 1 : 0);
    }
    double lightest = std::numeric_limits<double>::infinity();
    for (std::size_t p = 0; p < n; ++p)
      lightest = std::min(lightest, P.mass[p] * specific_heat_[static_cast<std::size_t>(P.material[p])]);
    negligible_capacity_ = std::isfinite(lightest) ? 1e-10 * lightest : 0.0;
    for (const ThermalWallCondition<D>& c : problem.thermal.walls)
      if (c.kind == ThermalWallKind::flux || c.kind == ThermalWallKind::convection) boundary_measure_ = true;
    if (!problem.thermal.edge_loads.empty()) edge_source_.assign(n, 0.0);
    for (const WallSpec<D>& w : problem.walls)
      if (w.kind == WallKind::contact) wall_friction_ = true;
    dt_limit_ = thermal_stable_time_step<D>(problem, P, problem.time.cfl);
  }

  /// Thermal part of the trial Cauchy stress of a particle (000 eq. 3; DESIGN §4) [Pa].
  Mat<D> stress(int material, const Mat<D>& F, double temperature) const {
    const std::size_t m = static_cast<std::size_t>(material);
    return thermal_cauchy_stress<D>(bulk_[m], expansion_[m], temperature, reference_[m], F.determinant());
  }

  /// Conduction limit from the last thermal stage (C_cfl ρ c h² / (2 D κ)) [s].
  double dt_limit() const { return dt_limit_; }

  /// Friction work [J] of a rigid contact wall at field f of node i in this step: it all becomes
  /// heat of the material (the wall is rigid and has no heat capacity in the model).
  void add_wall_friction_heat(int f, std::size_t i, double work) { wall_heat_[static_cast<std::size_t>(f)][i] += work; }

  /// Nodal temperature of field f at active node i after the re-projection of this step [K].
  double node_temperature(int f, std::size_t i) const { return temperature_[static_cast<std::size_t>(f)][i]; }

  /// Interface temperature max(θ₀ᵢ, θ₁ᵢ) of a two-field node for the friction law (000 eq. 15) [K].
  double interface_temperature(std::size_t i) const { return std::max(temperature_[0][i], temperature_[1][i]); }

  /// First half of the thermal stage, after the mechanical P2G: nodal capacities and the
  /// re-projected nodal temperatures θⁿ (000 eq. 56; Alg. 2 lines 4, 19-21), which the contact
  /// friction law of this step reads. `Host` is the solver's Impl: it supplies the race-free
  /// scatter, the particle-to-field map, separability and the active grid.
  template <ShapeFunctionKind Kind, bool Partitioned, class Host>
  void begin(Host& host) {
    auto& P = host.problem.particles;
    const std::size_t nodes = host.node_mass[0].size();
    constexpr int fields = Partitioned ? 2 : 1;
    for (int f = 0; f < fields; ++f) {
      capacity_[f].assign(nodes, 0.0);
      heat_[f].assign(nodes, 0.0);
      load_[f].assign(nodes, 0.0);
      temperature_[f].assign(nodes, 0.0);
      rate_[f].assign(nodes, 0.0);
      if (wall_friction_) wall_heat_[f].assign(nodes, 0.0);
      if (boundary_measure_) domain_gradient_[f].assign(nodes, Vec<D>::Zero());
    }
    auto field = [&](std::int64_t p, std::size_t i) -> int {
      if constexpr (Partitioned) return host.field_of(p, i);
      else return 0;
    };

    // 1. Capacity and re-projected temperature per field (000 eq. 56; Alg. 2 lines 4, 19-21).
    host.template for_each_particle_scatter<Kind>([&](std::int64_t p, const Stencil<D>& s) {
      const double mc = P.mass[p] * specific_heat_[static_cast<std::size_t>(P.material[p])];
      const double mct = mc * P.temperature[p];
      const double volume = boundary_measure_ ? P.volume0[p] * P.F[p].determinant() : 0.0;
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        const int f = field(p, i);
        capacity_[f][i] += s.weight[e] * mc;
        heat_[f][i] += s.weight[e] * mct;
        if (boundary_measure_) domain_gradient_[f][i] += volume * s.gradient[e];
      }
    });
    const std::int64_t count = static_cast<std::int64_t>(nodes);
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < count; ++i) {
      for (int f = 0; f < fields; ++f)
        if (capacity_[f][i] > negligible_capacity_) temperature_[f][i] = heat_[f][i] / capacity_[f][i];
      if constexpr (Partitioned) {
        // Fields that move as one (not separable) are one body thermally too: one temperature.
        if (capacity_[0][i] > negligible_capacity_ && capacity_[1][i] > negligible_capacity_ &&
            !host.node_separable(static_cast<std::size_t>(i))) {
          const double theta = (heat_[0][i] + heat_[1][i]) / (capacity_[0][i] + capacity_[1][i]);
          temperature_[0][i] = temperature_[1][i] = theta;
        }
      }
    }
  }

  /// Second half, after the contact and wall exchanges of this step: heat loads, nodal rates and the
  /// particle temperatures θⁿ⁺¹ (000 Alg. 2), before the stress update that uses them.
  template <ShapeFunctionKind Kind, bool Partitioned, class Host>
  void finish(Host& host, double dt) {
    auto& P = host.problem.particles;
    const ThermalSpec<D>& spec = host.problem.thermal;
    const std::int64_t count = static_cast<std::int64_t>(capacity_[0].size());
    constexpr int fields = Partitioned ? 2 : 1;
    auto field = [&](std::int64_t p, std::size_t i) -> int {
      if constexpr (Partitioned) return host.field_of(p, i);
      else return 0;
    };
    if constexpr (Partitioned) merge_perfect_contacts(host, dt);

    // 2. Conduction Q_i^int = Σ_p V_p q_p·∇S̄_ip with q_p = −κ_p ∇θ(x_p) (000 eq. 18, 58), and heat
    //    input through body edges carried by particles, Q_i += S̄_ip a_p q̄ (eq. 57).
    const bool edges = !edge_source_.empty();
    if (edges) update_edge_sources(spec, P);
    host.template for_each_particle_scatter<Kind>([&](std::int64_t p, const Stencil<D>& s) {
      Vec<D> gradient = Vec<D>::Zero();
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        gradient += temperature_[field(p, i)][i] * s.gradient[e];
      }
      const double volume = P.volume0[p] * P.F[p].determinant();
      const Vec<D> volume_flux = -(volume * conductivity_[static_cast<std::size_t>(P.material[p])]) * gradient;
      const double source = edges ? edge_source_[p] : 0.0;
      for (int e = 0; e < s.count; ++e) {
        const std::size_t i = static_cast<std::size_t>(s.node[e]);
        load_[field(p, i)][i] += volume_flux.dot(s.gradient[e]) + s.weight[e] * source;
      }
    });

    // 3. Thermal conditions on walls (000 eq. 44, 57); heat across and from separable contacts.
    if (!spec.walls.empty()) apply_wall_loads(host, fields);
    if constexpr (Partitioned) add_contact_heat(host, dt);
    if (wall_friction_)
      for (int f = 0; f < fields; ++f)
        for (std::int64_t i = 0; i < count; ++i) load_[f][i] += wall_heat_[f][i] / dt;

    // 4. Nodal rates (eq. 55); two fields that are not separable share one rate (Alg. 2 line 10).
#pragma omp parallel for schedule(static)
    for (std::int64_t i = 0; i < count; ++i) {
      for (int f = 0; f < fields; ++f)
        if (capacity_[f][i] > negligible_capacity_) rate_[f][i] = load_[f][i] / capacity_[f][i];
      if constexpr (Partitioned) {
        if (capacity_[0][i] > negligible_capacity_ && capacity_[1][i] > negligible_capacity_ &&
            (!host.node_separable(static_cast<std::size_t>(i)) || merged_[static_cast<std::size_t>(i)])) {
          const double shared = (load_[0][i] + load_[1][i]) / (capacity_[0][i] + capacity_[1][i]);
          rate_[0][i] = rate_[1][i] = shared;
        }
      }
    }
    if (!fixed_nodes_.empty()) {  // θ = θ̄ on Γ_θ: the rate that takes the node there in this step
      for (const auto& [i, f, value] : fixed_nodes_)
        rate_[static_cast<std::size_t>(f)][i] = (value - temperature_[static_cast<std::size_t>(f)][i]) / dt;
    }

    // 5. Particles: θ_p += Δt Σ_i S̄_ip θ̇_i (eq. 62), blended with the PIC value when
    //    thermal_pic_fraction > 0 (TimeSpec), then the local sources of the mechanical step
    //    that just ended (eq. 39, 28, 40), and the conduction limit for the next step.
    const std::int64_t n = static_cast<std::int64_t>(P.size());
    const double h2 = host.grid.cell_size * host.grid.cell_size;
    const double courant = host.problem.time.cfl;
    const double pic = host.problem.time.thermal_pic_fraction;  // 0 = eq. 62 alone
    double limit = std::numeric_limits<double>::infinity();
#pragma omp parallel reduction(min : limit)
    {
      Stencil<D> s;
#pragma omp for schedule(static)
      for (std::int64_t p = 0; p < n; ++p) {
        Host::template fill_stencil<Kind>(P, p, host.grid, s);
        double change = 0.0;
        for (int e = 0; e < s.count; ++e) {
          const std::size_t i = static_cast<std::size_t>(s.node[e]);
          change += s.weight[e] * rate_[field(p, i)][i];
        }
        const std::size_t m = static_cast<std::size_t>(P.material[p]);
        double theta = P.temperature[p] + dt * change;
        if (pic > 0.0) {  // PIC part: Σ S̄ (θ_i + Δt θ̇_i), a convex combination of nodal temperatures
          double projected = 0.0;
          for (int e = 0; e < s.count; ++e) {
            const std::size_t i = static_cast<std::size_t>(s.node[e]);
            const int f = field(p, i);
            projected += s.weight[e] * (temperature_[f][i] + dt * rate_[f][i]);
          }
          theta = (1.0 - pic) * theta + pic * projected;
        }
        const double J = P.F[p].determinant();
        const double density0 = P.mass[p] / P.volume0[p];
        const double d = P.damage[p];
        // Elastic structural heating over last_J → J at fixed damage (eq. 39, integrated exactly).
        if (expansion_[m] != 0.0 && J != last_J_[p])
          theta *= adiabatic_temperature_ratio(bulk_[m], expansion_[m], density0, specific_heat_[m],
                                               coupling_fraction(d, degradation_[m], J), last_J_[p], J);
        // Damage dissipation and coupling heat of the damage increment (eq. 28, 40).
        if (damages_[m] && d > last_damage_[p]) {
          const NeoHookean& model = host.models[m];
          const double psi = model.template energy_density<D>(P.F[p]);
          const double degradable =
              std::clamp(degradable_energy<D>(model, P.F[p], degradation_[m]), 0.0, psi);
          // The coupling energy is released only where damage degrades it (coupling_fraction).
          const double released = coupling_fraction(1.0, degradation_[m], J) < 1.0 ? 1.0 : 0.0;
          theta += damage_heat_density(degradable, bulk_[m], released * expansion_[m], reference_[m], J,
                                       d - last_damage_[p]) /
                   (density0 * specific_heat_[m]);
        }
        P.temperature[p] = theta;
        last_J_[p] = J;
        last_damage_[p] = d;
        if (conductivity_[m] > 0.0)
          limit = std::min(limit, courant * density0 / J * specific_heat_[m] * h2 / (2.0 * D * conductivity_[m]));
      }
    }
    dt_limit_ = limit;
  }

 private:
  /// a_p q̄ or a_p h (θ_∞ − θ_p) per loaded particle [W per unit thickness in 2D].
  void update_edge_sources(const ThermalSpec<D>& spec, const Particles<D>& P) {
    std::fill(edge_source_.begin(), edge_source_.end(), 0.0);
    for (const HeatFluxLoad& load : spec.edge_loads)
      for (std::size_t k = 0; k < load.particles.size(); ++k) {
        const std::size_t p = static_cast<std::size_t>(load.particles[k]);
        const double q = load.kind == ThermalWallKind::convection
                             ? load.film_coefficient * (load.temperature - P.temperature[p])
                             : load.flux;
        edge_source_[p] += load.boundary_measure[k] * q;
      }
  }

  /// Walls: prescribed temperature at the nodes on or behind the plane (Γ_θ); flux and convection
  /// on the material face near the plane (Γ_q, Γ_h), with the face measure at node i from the
  /// divergence theorem, ∫_Ω ∇S̄_i dV = ∮ S̄_i n dΓ: −n_wall · Σ_p V_p ∇S̄_ip is ∫ S̄_i dΓ over the
  /// face that looks at the wall (the 004 eq. 6 idea applied to a wall). Nodes up to two cells in
  /// front of the plane count, so a face between node rows is covered.
  template <class Host>
  void apply_wall_loads(Host& host, int fields) {
    fixed_nodes_.clear();
    const std::int64_t nodes = static_cast<std::int64_t>(capacity_[0].size());
    const double h = host.grid.cell_size;
    const double tolerance = 1e-9 * h;
    for (const ThermalWallCondition<D>& c : host.problem.thermal.walls) {
      if (c.kind == ThermalWallKind::insulated) continue;
      const ThermalWallCondition<D>& wall = c;
      const Vec<D> shift = wall.velocity.displacement(host.time);
      const Vec<D> point = wall.point + shift;
      for (std::int64_t i = 0; i < nodes; ++i) {
        const Vec<D> node_point = host.grid.position(host.grid.global(i));
        const double distance = (node_point - point).dot(wall.normal);
        if (distance > 2.0 * h || !wall.region.contains(node_point, shift, tolerance)) continue;
        for (int f = 0; f < fields; ++f) {
          if (!(capacity_[f][i] > negligible_capacity_)) continue;
          if (c.kind == ThermalWallKind::temperature) {
            if (distance <= tolerance) fixed_nodes_.push_back({static_cast<std::size_t>(i), f, c.temperature});
            continue;
          }
          const double measure = std::max(0.0, -domain_gradient_[f][i].dot(wall.normal));
          const double q = c.kind == ThermalWallKind::flux ? c.flux
                                                           : c.film_coefficient * (c.temperature - temperature_[f][i]);
          load_[f][i] += measure * q;
        }
      }
    }
  }

  /// Heat exchanged at separable two-field nodes in contact this step (000 eq. 11-14, 79-82):
  /// conductance h_c = h₀ |p/p₀|^ε with the contact pressure p = f_n / A_c from this step's normal
  /// contact impulse (f_n = N A_c = impulse/Δt) and area A_c (004 eq. 11), so the nodal load is
  /// Q₀ = h_c A_c (θ₁ − θ₀) = −Q₁; for ε = 1 this is γ̄ |f_n| [θ] of eq. (82) and needs no area.
  /// Contacts that would equalise within the step are merged instead (merge_perfect_contacts), so
  /// the explicit flow never overshoots. The friction work W of the step is heat W/Δt, half into each side (eq. 14, 82).
  /// Conductance of a separable contact node in contact this step, h_c A_c [W/K per unit thickness]
  /// (000 eq. 12-13, 82): 0 when the node is not in contact or nothing conducts.
  template <class Host>
  double contact_conductance(const Host& host, std::size_t k, double dt) const {
    const ThermalSpec<D>& spec = host.problem.thermal;
    const double impulse = host.node_normal_impulse[k];
    if (!(spec.contact_conductance > 0.0) || !(impulse > 0.0)) return 0.0;
    const double force = impulse / dt;
    if (spec.contact_exponent == 1.0) return spec.contact_conductance / spec.contact_pressure * force;
    const double area = host.node_contact_area[k];
    if (!(area > 0.0)) return 0.0;
    return spec.contact_conductance * std::pow(force / (area * spec.contact_pressure), spec.contact_exponent) * area;
  }

  /// A contact whose conductance would equalise the two nodal temperatures within one step
  /// (h_c A_c Δt ≥ C₀C₁/(C₀+C₁)) is thermally perfect: its fields share one temperature and one
  /// rate, as non-separable fields do (Alg. 2 line 10). Exchanging the capped flow explicitly
  /// instead would leave a numerical resistance Δt(1/C₀ + 1/C₁) at the node.
  template <class Host>
  void merge_perfect_contacts(const Host& host, double dt) {
    merged_.assign(capacity_[0].size(), 0);
    for (std::size_t k = 0; k < host.two_field_nodes.size(); ++k) {
      const std::size_t i = static_cast<std::size_t>(host.two_field_nodes[k]);
      const double c0 = capacity_[0][i], c1 = capacity_[1][i];
      if (!(c0 > negligible_capacity_ && c1 > negligible_capacity_) || !host.node_separable(i)) continue;
      if (contact_conductance(host, k, dt) * dt < c0 * c1 / (c0 + c1)) continue;
      merged_[i] = 1;
      const double theta = (heat_[0][i] + heat_[1][i]) / (c0 + c1);
      temperature_[0][i] = temperature_[1][i] = theta;
    }
  }

  template <class Host>
  void add_contact_heat(Host& host, double dt) {
    const ThermalSpec<D>& spec = host.problem.thermal;
    const bool conducts = spec.contact_conductance > 0.0;
    const std::size_t count = host.two_field_nodes.size();
    for (std::size_t k = 0; k < count; ++k) {
      const std::size_t i = static_cast<std::size_t>(host.two_field_nodes[k]);
      const double c0 = capacity_[0][i], c1 = capacity_[1][i];
      if (!(c0 > negligible_capacity_ && c1 > negligible_capacity_) || !host.node_separable(i)) continue;
      const double friction_heat = host.node_friction_work[k] / dt;
      load_[0][i] += 0.5 * friction_heat;
      load_[1][i] += 0.5 * friction_heat;
      if (!conducts || merged_[i]) continue;
      const double conductance_area = contact_conductance(host, k, dt);
      if (!(conductance_area > 0.0)) continue;
      const double jump = temperature_[1][i] - temperature_[0][i];
      const double equalising = c0 * c1 / (c0 + c1) / dt;
      const double flow = std::min(conductance_area, equalising) * jump;  // into field 0 [W]
      load_[0][i] += flow;
      load_[1][i] -= flow;
    }
  }

  struct FixedNode {
    std::size_t node;
    int field;
    double value;
  };

  std::vector<double> bulk_, expansion_, reference_, conductivity_, specific_heat_;
  std::vector<Degradation> degradation_;
  std::vector<char> damages_;
  std::vector<double> last_J_, last_damage_;  ///< J and d when the sources were last booked
  std::vector<double> edge_source_;
  std::array<std::vector<double>, 2> capacity_, heat_, load_, temperature_, rate_, wall_heat_;
  std::array<std::vector<Vec<D>>, 2> domain_gradient_;
  std::vector<FixedNode> fixed_nodes_;
  std::vector<char> merged_;  ///< per node: a thermally perfect contact this step
  bool boundary_measure_ = false;
  bool wall_friction_ = false;  ///< a contact wall may do friction work
  double negligible_capacity_ = 0.0;
  double dt_limit_ = std::numeric_limits<double>::infinity();
};

}  // namespace fragmpm::mpm
