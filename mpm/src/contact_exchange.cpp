// Two-field contact momentum exchange, [NBS18] §2.6-2.10. All friction laws are evaluated in
// impulse form, s = S_slide A_c Δt, so laws that do not need the contact area never divide by it.
#include "fragmpm/mpm/contact_exchange.hpp"

#include <algorithm>
#include <cmath>
#include <variant>

namespace fragmpm::mpm {
namespace {

/// The quantities every friction law may read, in impulse form ([NBS18] eq. (15)).
struct StickImpulses {
  double normal = 0.0;        ///< N A_c Δt = −d_n > 0 [N s]
  double tangential = 0.0;    ///< d_t = S_stick A_c Δt ≥ 0 [N s]
  double reduced_mass = 0.0;  ///< m_red [kg]
  double area_dt = 0.0;       ///< A_c Δt [m² s]
  double temperature = 0.0;   ///< [K]
};

// s = S_slide A_c Δt for each law. A law that sticks returns s ≥ d_t.

double sliding_impulse(const CoulombFriction& law, const StickImpulses& x) {
  return law.coefficient * x.normal;  // [NBS18] eq. (20): S_slide A_c Δt = −μ d_n
}

double sliding_impulse(const VelocityDependentFriction& law, const StickImpulses& x) {
  // [NBS18] eq. (22) with the final slip speed |Δv′| = (d_t − s)/m_red (eq. (21)):
  //   s = (μ₀ + k (d_t − s)/m_red) N*,  N* = N A_c Δt = −d_n,
  // solved for s: s = (m_red μ₀ + k d_t) N* / (m_red + k N*). This is eq. (23) with its denominator
  // written with N* = −d_n (the printed "m_red + k d_n" would need d_n taken as a magnitude).
  // Sticking (s ≥ d_t) happens exactly when d_t ≤ μ₀ N*.
  const double denominator = x.reduced_mass + law.slope * x.normal;
  if (denominator <= 0.0)
    return law.coefficient * x.normal;  // k < 0 so steep that eq. (22) has no root
  return (x.reduced_mass * law.coefficient + law.slope * x.tangential) * x.normal / denominator;
}

double sliding_impulse(const AdhesiveFriction& law, const StickImpulses& x) {
  return law.shear_strength * x.area_dt + law.coefficient * x.normal;  // [NBS18] eq. (24)
}

double sliding_impulse(const SmoothStaticDynamicFriction& law, const StickImpulses& x) {
  // Sticks while d_t ≤ μ_s N* ([NBS18] §2.8, below eq. (43)).
  const double static_impulse = law.static_coefficient * x.normal;
  if (x.tangential <= static_impulse) return static_impulse;
  // Our inversion of eq. (42) at the final slip speed w = (d_t − s)/m_red (eq. (21)). With
  // k* = v½ m_red and D* = d_t + k*, multiplying s = N* (μ_s v½ + μ_d w)/(v½ + w) by m_red(v½ + w)
  // gives the quadratic
  //   f(s) = s² − (D* + μ_d N*) s + (μ_s k* + μ_d d_t) N* = 0.
  // f(0) = (μ_s k* + μ_d d_t) N* ≥ 0 and f(d_t) = k* (μ_s N* − d_t) < 0 while sliding, so exactly
  // one root lies in [0, d_t): the smaller one. Its discriminant is
  //   ((D* + μ_d N*)/2)² − (μ_s k* + μ_d d_t) N* = ((D* − μ_d N*)/2)² − (μ_s − μ_d) k* N*,
  // which is eq. (43) times N*². We evaluate the smaller root as c / (b/2 + √disc) (product of the
  // roots is c) to avoid the cancellation of b/2 − √disc when k* is small.
  const double k_star = law.half_velocity * x.reduced_mass;
  const double d_star = x.tangential + k_star;
  const double half_b = 0.5 * (d_star + law.dynamic_coefficient * x.normal);
  const double half_difference = 0.5 * (d_star - law.dynamic_coefficient * x.normal);
  const double c =
      (law.static_coefficient * k_star + law.dynamic_coefficient * x.tangential) * x.normal;
  const double discriminant =
      half_difference * half_difference -
      (law.static_coefficient - law.dynamic_coefficient) * k_star * x.normal;
  return c / (half_b + std::sqrt(std::max(discriminant, 0.0)));  // half_b > 0 since d_t > 0 here
}

double sliding_impulse(const ThermalSofteningFriction& law, const StickImpulses& x) {
  return friction_coefficient(law, x.temperature) *
         x.normal;  // Coulomb with μ(θ) of [XLS21] eq. (15)
}

/// Elliptical adhesion criterion of [NBS18] eq. (25) in impulse form: the interface holds while
/// (d_t / (S_a A_c Δt))² + (d_n / (N_a A_c Δt))² ≤ 1. A zero strength holds only a zero impulse.
bool adhesion_holds(const AdhesiveFriction& law, double d_n, double d_t, double area_dt) {
  const double shear_capacity = law.shear_strength * area_dt;
  const double tensile_capacity = law.tensile_strength * area_dt;
  if (d_t > 0.0 && !(shear_capacity > 0.0)) return false;
  if (d_n != 0.0 && !(tensile_capacity > 0.0)) return false;
  const double shear = d_t > 0.0 ? d_t / shear_capacity : 0.0;
  const double tension = d_n != 0.0 ? d_n / tensile_capacity : 0.0;
  return shear * shear + tension * tension <= 1.0;
}

}  // namespace

template <int D>
ContactExchange<D> exchange_momentum(const ContactNode<D>& node, const FrictionLaw& law, double dt,
                                     FrictionWorkOrder order) {
  ContactExchange<D> out;
  if (!(node.mass_a > 0.0) || !(node.mass_b > 0.0) || std::isinf(node.mass_a)) return out;
  const bool rigid_b = std::isinf(node.mass_b);
  // [NBS18] §2.12: against a rigid b, v_cm = v_b and m_red = m_a; no infinite mass enters
  // arithmetic.
  const double m_red =
      rigid_b ? node.mass_a : node.mass_a * node.mass_b / (node.mass_a + node.mass_b);

  // Stick momentum change Δp_a = m_a v_cm − p_a = m_red (v_b − v_a) ([NBS18] eq. (12), (14)).
  const Vec<D> stick = m_red * (node.velocity_b - node.velocity_a);
  const double d_n = stick.dot(node.normal);  // [NBS18] eq. (15)
  const Vec<D> tangential = stick - d_n * node.normal;
  const double d_t = tangential.norm();
  const double area_dt = node.area * dt;

  // Contact needs approach, Δv·n < 0 ⟺ d_n < 0, and a closed gap ([NBS18] §2.4).
  if (!(d_n < 0.0) || !node.gap_closed) {
    // Separated surfaces move freely unless tensile adhesion holds them ([NBS18] eq. (25)).
    const auto* adhesive = std::get_if<AdhesiveFriction>(&law);
    if (adhesive != nullptr && adhesive->tensile_strength > 0.0 &&
        adhesion_holds(*adhesive, d_n, d_t, area_dt)) {
      out.in_contact = true;
      out.momentum_change_a = stick;
      out.normal_impulse = -d_n;
    }
    return out;
  }

  StickImpulses x;
  x.normal = -d_n;
  x.tangential = d_t;
  x.reduced_mass = m_red;
  x.area_dt = area_dt;
  x.temperature = node.temperature;
  const double s =
      std::max(0.0, std::visit([&x](const auto& l) { return sliding_impulse(l, x); }, law));

  out.in_contact = true;
  out.normal_impulse = x.normal;
  if (d_t <= s) {  // S_stick ≤ S_slide: the fields stick ([NBS18] §2.6 step 1)
    out.momentum_change_a = stick;
    return out;
  }

  // Slide: keep the full normal change, limit the tangential one ([NBS18] eq. (17)).
  const Vec<D> t_hat = tangential / d_t;
  out.sliding = true;
  out.momentum_change_a = d_n * node.normal + s * t_hat;
  out.slip_speed = (d_t - s) / m_red;  // [NBS18] eq. (21)

  if (order == FrictionWorkOrder::lumped_slip) {
    // The step's energy identity (contact_energy.cpp) at a node where the exchange adds the
    // impulse J to field a and −J to b: with l the lumped velocities and b = Δt f/m the force
    // increments, kinetic + strain − external work changes by
    //   J·(l_a − l_b) + |J|²/(2 m_red) − ½ Σ_f m_f |b_f|²,
    // the same for FLIP and APIC. J = J_n n + s t̂ with n ⊥ t̂ gives the tangential part
    //   −s w₀ + s²/(2 m_red),  w₀ = (l_b − l_a)·t̂,
    // w₀ the slip of the lumped velocities (the mass-weighted mean velocities of the particles at
    // the node) against the friction impulse. Friction takes s w₀: the friction impulse on the
    // slip the material brings. The s²/(2 m_red) stays with the explicit error ½ m_red |Δb_t|²,
    // which it cancels exactly at a node sliding at constant speed (Δb_t = s/m_red), in the
    // remainder that contact_energy.cpp books as contact loss. Unlike [NBS18] eq. (27) and
    // (34)-(36), s w₀ reads no force increment: a light node, whose trial velocity a force can
    // push to many times the material's speed, books no friction for that speed, and at the
    // corners of a confined press the friction no longer depends on Δt (docs/design.md §2.4).
    // After another wall or contact changed the node this step, v − Δt f/m carries that change,
    // which is what the identity needs for exchanges applied one after another. A slip that the
    // force reversed within the step (w₀ < 0) books none.
    const Vec<D> lumped_a = node.velocity_a - dt * node.force_a / node.mass_a;
    const Vec<D> lumped_b =
        rigid_b ? node.velocity_b : Vec<D>(node.velocity_b - dt * node.force_b / node.mass_b);
    out.friction_work = std::max(0.0, s * (lumped_b - lumped_a).dot(t_hat));
    return out;
  }
  // Friction work. First order ([NBS18] eq. (27)): W₁ = s (d_t − s)/m_red, the sliding impulse
  // times the final slip speed. Second order (eq. (31)-(36)): the relative slip velocity varies
  // linearly over the step, v(t) = (d_t − s)/m_red + (f_t − s/Δt)(t − Δt)/m_red with f_t = Δf_a·t̂
  // (eq. (29)-(30)); W₂ = s (f_t Δt − s)/m_red (eq. (33)) and v(0) = (W₁ − W₂)/s (eq. (32)). If
  // v(0) ≥ 0 the slip lasted the whole step, ΔW = W₁ − W₂/2 (eq. (34)) — the exact work s (v(0) +
  // v(Δt))/2 for a constant acceleration, equal to the tangential kinetic energy removed when f_t =
  // 0. Otherwise slip began at t_s = Δt (1 − W₁/W₂) (eq. (35)) and ΔW = W₁²/(2 W₂) (eq. (36)); W₂ >
  // W₁ ≥ 0 there.
  const double w1 = s * (d_t - s) / m_red;
  if (order == FrictionWorkOrder::first) {
    out.friction_work = w1;
    return out;
  }
  // Δf_a = (m_a f_b − m_b f_a)/(m_a + m_b) (eq. (30)); → −f_a for a rigid b, whose motion is
  // prescribed.
  const Vec<D> delta_f = rigid_b
                             ? Vec<D>(-node.force_a)
                             : Vec<D>((node.mass_a * node.force_b - node.mass_b * node.force_a) /
                                      (node.mass_a + node.mass_b));
  const double f_t = delta_f.dot(t_hat);
  const double w2 = s * (f_t * dt - s) / m_red;
  out.friction_work = (w2 <= w1) ? w1 - 0.5 * w2 : w1 * w1 / (2.0 * w2);
  return out;
}

double contact_area_2d(double node_volume, double volume_a, double volume_b, double cell_size,
                       double thickness) {
  return thickness * contact_area_3d(node_volume, volume_a, volume_b, cell_size);
}

double contact_area_3d(double node_volume, double volume_a, double volume_b, double cell_size) {
  const double smaller = std::min(volume_a, volume_b);
  if (!(cell_size > 0.0) || !(smaller > 0.0) || !(node_volume > 0.0)) return 0.0;
  return std::sqrt(2.0 * node_volume * smaller) / cell_size;  // [NBS18] eq. (11)
}

template <int D>
double contact_area_from_gradients(const Vec<D>& gradient_a, const Vec<D>& gradient_b,
                                   const Vec<D>& normal) {
  return std::min(std::abs(gradient_a.dot(normal)), std::abs(gradient_b.dot(normal)));
}

template double contact_area_from_gradients<2>(const Vec<2>&, const Vec<2>&, const Vec<2>&);
template double contact_area_from_gradients<3>(const Vec<3>&, const Vec<3>&, const Vec<3>&);
template ContactExchange<2> exchange_momentum<2>(const ContactNode<2>&, const FrictionLaw&, double,
                                                 FrictionWorkOrder);
template ContactExchange<3> exchange_momentum<3>(const ContactNode<3>&, const FrictionLaw&, double,
                                                 FrictionWorkOrder);

}  // namespace fragmpm::mpm
