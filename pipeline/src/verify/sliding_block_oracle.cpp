// Rigid-block oracle of V2 ([NBS18] appendix eq. (46)-(54)).
#include "fragmpm/pipeline/sliding_block_oracle.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>

namespace fragmpm::pipeline {
namespace {

struct Rates {
  double alpha = 0.0;  ///< α = R N / (ρ h t_s) [m/s³]
  double beta = 0.0;   ///< β = (μ_s − μ_d) N / (ρ h) [m/s²]
  double gamma = 0.0;  ///< γ = k N / (ρ h) [1/s]
};

double ramp_duration(const SlidingBlockLoading& b) {
  return b.end_time - b.tangential_start;
}  // t_s

Rates rates(const SlidingBlockLoading& b, const RigidBlockFriction& f) {  // eq. (49)
  const double mass_per_area = b.density * b.height;
  return {b.ratio * b.normal_stress / (mass_per_area * ramp_duration(b)),
          (f.static_coefficient - f.dynamic_coefficient) * b.normal_stress / mass_per_area,
          f.slope * b.normal_stress / mass_per_area};
}

/// Friction traction S_slide(v) of a law on the block [Pa] (eq. (41); [NBS18] eq. (42); [XLS21] eq.
/// (15) at θ_ref).
double sliding_traction(const mpm::FrictionLaw& law, double normal_stress, double speed) {
  struct Visitor {
    double n, v;
    double operator()(const mpm::CoulombFriction& l) const { return l.coefficient * n; }
    double operator()(const mpm::VelocityDependentFriction& l) const {
      return mpm::friction_coefficient(l, v) * n;
    }
    double operator()(const mpm::AdhesiveFriction& l) const {
      return l.coefficient * n + l.shear_strength;
    }
    double operator()(const mpm::SmoothStaticDynamicFriction& l) const {
      return mpm::friction_coefficient(l, v) * n;
    }
    double operator()(const mpm::ThermalSofteningFriction& l) const {
      return mpm::friction_coefficient(l, l.reference_temperature) * n;
    }
  };
  return std::visit(Visitor{normal_stress, speed}, law);
}

}  // namespace

SlidingBlockLoading sliding_block_loading(double density, double height, double length,
                                          double coulomb_coefficient, double ratio,
                                          double final_speed, double distance,
                                          double ramp_fraction) {
  const double sliding_time = 3.0 * distance / final_speed;                // T = 3x/v
  const double ramp = sliding_time / (1.0 - coulomb_coefficient / ratio);  // t_s, from eq. (47)
  SlidingBlockLoading b;
  b.density = density;
  b.height = height;
  b.length = length;
  b.ratio = ratio;
  b.end_time = ramp / (1.0 - ramp_fraction);
  b.tangential_start = ramp_fraction * b.end_time;
  b.normal_ramp_end = b.tangential_start;
  const double alpha = 2.0 * final_speed / (sliding_time * sliding_time);  // v = αT²/2
  b.normal_stress = alpha * density * height * ramp / ratio;               // eq. (49)
  return b;
}

std::optional<RigidBlockFriction> rigid_block_friction(const mpm::FrictionLaw& law) {
  if (const auto* c = std::get_if<mpm::CoulombFriction>(&law))
    return RigidBlockFriction{c->coefficient, c->coefficient, 0.0, 0.0};
  if (const auto* v = std::get_if<mpm::VelocityDependentFriction>(&law))
    return RigidBlockFriction{v->coefficient, v->coefficient, v->slope, 0.0};
  if (const auto* a = std::get_if<mpm::AdhesiveFriction>(&law))
    return RigidBlockFriction{a->coefficient, a->coefficient, 0.0, a->shear_strength};
  if (const auto* s = std::get_if<mpm::SmoothStaticDynamicFriction>(&law);
      s && s->half_velocity == 0.0)
    return RigidBlockFriction{s->static_coefficient, s->dynamic_coefficient, 0.0, 0.0};
  return std::nullopt;
}

double rigid_block_onset(const SlidingBlockLoading& b, const RigidBlockFriction& f) {
  if (!(b.ratio > 0.0) || !(b.normal_stress > 0.0)) return std::numeric_limits<double>::infinity();
  return b.tangential_start + (f.static_coefficient + f.adhesion / b.normal_stress) *
                                  ramp_duration(b) / b.ratio;  // eq. (47)
}

double rigid_block_velocity(const SlidingBlockLoading& b, const RigidBlockFriction& f, double t) {
  const double T = t - rigid_block_onset(b, f);
  if (!(T > 0.0)) return 0.0;
  const Rates r = rates(b, f);
  if (r.gamma == 0.0) return 0.5 * r.alpha * T * T + r.beta * T;         // eq. (50), k = 0
  const double psi = r.alpha / r.gamma, phi = (r.beta - psi) / r.gamma;  // eq. (51)
  return psi * T + phi * -std::expm1(-r.gamma * T);                      // eq. (50), k ≠ 0
}

double rigid_block_friction_work(const SlidingBlockLoading& b, const RigidBlockFriction& f,
                                 double t) {
  const double T = t - rigid_block_onset(b, f);
  if (!(T > 0.0)) return 0.0;
  const Rates r = rates(b, f);
  const double constant_part = f.dynamic_coefficient * b.normal_stress + f.adhesion;  // μ_d N + S_a
  if (r.gamma == 0.0)                                                                 // eq. (53)
    return b.length * constant_part * (r.alpha * T * T * T / 6.0 + 0.5 * r.beta * T * T);
  // k ≠ 0: Q/(l b) = (μ_d N + S_a) ∫v dt + k N ∫v² dt with v = ψT + φ(1 − e^{−γT}) (eq. (50),
  // (52)):
  //   ∫v  = ψT²/2 + φ (T − (1 − e^{−γT})/γ)
  //   ∫v² = ψ²T³/3 + φ² (T − (3 − 4e^{−γT} + e^{−2γT})/(2γ)) + ψφ (T² − 2(1 − (1 + γT)
  //   e^{−γT})/γ²).
  // (The printed eq. (54) swaps ψ and φ in the first bracket and leaves the ψφ term outside k N.)
  const double g = r.gamma, psi = r.alpha / g, phi = (r.beta - psi) / g;
  const double one_minus_e1 = -std::expm1(-g * T), e1 = std::exp(-g * T),
               e2 = std::exp(-2.0 * g * T);
  const double integral_v = 0.5 * psi * T * T + phi * (T - one_minus_e1 / g);
  const double integral_v2 = psi * psi * T * T * T / 3.0 +
                             phi * phi * (T - (3.0 - 4.0 * e1 + e2) / (2.0 * g)) +
                             psi * phi * (T * T - 2.0 * (1.0 - (1.0 + g * T) * e1) / (g * g));
  return b.length * (constant_part * integral_v + f.slope * b.normal_stress * integral_v2);
}

RigidBlockState integrate_rigid_block(const SlidingBlockLoading& b, const mpm::FrictionLaw& law,
                                      double t, int steps) {
  RigidBlockState s;
  const double n = b.normal_stress, mass_per_area = b.density * b.height, ramp = ramp_duration(b);
  // Onset when S(t) = R N (t − t₂)/t_s reaches the resistance at rest (eq. (46)-(47)).
  s.onset = b.tangential_start + sliding_traction(law, n, 0.0) * ramp / (b.ratio * n);
  if (!(t > s.onset) || steps < 1) return s;
  // y = (v, x, Q/b): v̇ = (S(t) − S_slide(v))/(ρ h), ẋ = v, Q̇/b = l S_slide(v) v.
  struct Y {
    double v, x, q;
  };
  auto rate = [&](double time, const Y& y) {
    // Sliding from the onset on: the resistance is the limit v → 0⁺, which differs from the value
    // at rest only for the sharp static/dynamic law (v½ = 0, μ_s at rest, μ_d once sliding).
    const double v = std::max(y.v, 1e-200);
    const double resistance = sliding_traction(law, n, v);
    const double push = b.ratio * n * (time - b.tangential_start) / ramp;
    return Y{(push - resistance) / mass_per_area, v, b.length * resistance * v};
  };
  const double h = (t - s.onset) / steps;
  Y y{0.0, 0.0, 0.0};
  double time = s.onset;
  for (int i = 0; i < steps; ++i) {
    const Y k1 = rate(time, y);
    const Y k2 =
        rate(time + 0.5 * h, {y.v + 0.5 * h * k1.v, y.x + 0.5 * h * k1.x, y.q + 0.5 * h * k1.q});
    const Y k3 =
        rate(time + 0.5 * h, {y.v + 0.5 * h * k2.v, y.x + 0.5 * h * k2.x, y.q + 0.5 * h * k2.q});
    const Y k4 = rate(time + h, {y.v + h * k3.v, y.x + h * k3.x, y.q + h * k3.q});
    y.v = std::max(0.0,
                   y.v + h / 6.0 * (k1.v + 2.0 * k2.v + 2.0 * k3.v + k4.v));  // no re-stick below 0
    y.x += h / 6.0 * (k1.x + 2.0 * k2.x + 2.0 * k3.x + k4.x);
    y.q += h / 6.0 * (k1.q + 2.0 * k2.q + 2.0 * k3.q + k4.q);
    time = s.onset + (i + 1) * h;
  }
  s.velocity = y.v;
  s.distance = y.x;
  s.friction_work = y.q;
  return s;
}

}  // namespace fragmpm::pipeline
