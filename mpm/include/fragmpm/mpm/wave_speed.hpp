#pragma once
// The longitudinal wave speed of a deformed particle, for the explicit step's stability limit.
//
// Why the reference density: the stiffest grid mode of a node has ω² = k_ii / m_i with
// k_ii = Σ_p V_p ∇N_ip · c_p · ∇N_ip over the particles' current volumes V_p = J V₀ and the spatial
// tangent c = c_τ / J (c_τ the tangent of the Kirchhoff stress τ = J σ), while m_i = Σ_p N_ip m_p.
// J cancels: ω² scales with c_τ / ρ₀, ρ₀ = m_p / V₀, and the speed that enters Δt < h / (√D c) is
// c = √(c_τ / ρ₀). The Cauchy modulus over the current density, (K + 4G/3) J / ρ₀, over-estimates
// it by √J for a particle that has opened up (a failed particle at J = 22 cut the step 4.7-fold)
// and under-estimates it by √J for a compressed one.
//
// The Kirchhoff longitudinal tangent ∂τ_ii / ∂ln λ_i along principal direction i:
//  * Hencky energy (τ = λ tr ε I + 2G ε in the log strain ε): K + 4G/3 at every F.
//  * Neo-Hookean of neo_hookean.hpp (τ = K ln J I + G J^(-2/3) dev b): differentiating with
//    ∂J^(-2/3)/∂ln λ_i = −(2/3) J^(-2/3) and ∂(λ_i² − tr b / 3)/∂ln λ_i = (4/3) λ_i² gives
//    K + G J^(-2/3) ((2/3) λ_i² + (2/9) tr b), largest along the largest stretch; K + 4G/3 at F =
//    I.
// The initial-stress term of the 1D wave equation, c² = (∂τ/∂ln λ − τ) / ρ₀, raises the speed of a
// compressed particle by |τ|; the bound adds the Frobenius norm of τ, which in tension errs on the
// safe side.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "fragmpm/mpm/neo_hookean.hpp"
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::mpm {

/// The elastic energy a material's particles follow.
enum class ElasticLaw {
  neo_hookean,  ///< neo_hookean.hpp
  hencky,       ///< the Hencky energy of the Hencky split and of phase-field materials
};

inline ElasticLaw elastic_law(const MaterialSpec& material) {
  return material.degradation == Degradation::hencky_spectral ||
                 std::holds_alternative<PhaseField>(material.damage)
             ? ElasticLaw::hencky
             : ElasticLaw::neo_hookean;
}

/// The share of the neo-Hookean's shear tangent a particle with damage d keeps: the
/// volumetric-deviatoric split and the isotropic degradation scale the whole deviatoric energy by
/// (1 − d); the tensile spectral split keeps the compressive principal stresses, which the shear
/// term stiffens, so it keeps the whole tangent.
inline double kept_shear_fraction(Degradation degradation, double damage) {
  const bool scales_deviator =
      degradation == Degradation::volumetric_deviatoric || degradation == Degradation::isotropic;
  return scales_deviator ? std::clamp(1.0 - damage, 0.0, 1.0) : 1.0;
}

/// Largest eigenvalue of b = F Fᵀ over the directions a wave can travel (in plane in 2D).
template <int D>
double largest_squared_stretch(const Mat<D>& F) {
  const Mat<D> b = F * F.transpose();
  if constexpr (D == 2) {
    const double half_trace = 0.5 * b.trace();
    const double discriminant = std::max(0.0, half_trace * half_trace - b.determinant());
    return half_trace + std::sqrt(discriminant);
  } else {
    Eigen::SelfAdjointEigenSolver<Mat<D>> eigen;
    eigen.computeDirect(b, Eigen::EigenvaluesOnly);
    return eigen.eigenvalues().maxCoeff();
  }
}

/// Upper bound of the longitudinal wave speed [m/s] of a particle with deformation F, Cauchy
/// stress σ (as stored, degraded and with any thermal part) and reference density ρ₀ = m / V₀.
/// `shear_fraction` (kept_shear_fraction) scales the neo-Hookean's shear tangent; the bulk
/// modulus is always counted.
template <int D>
double longitudinal_wave_speed(const NeoHookean& moduli, ElasticLaw law, const Mat<D>& F,
                               const Mat<D>& cauchy_stress, double reference_density,
                               double shear_fraction = 1.0) {
  const double J = F.determinant();
  double tangent = moduli.bulk_modulus + 4.0 * moduli.shear_modulus / 3.0;
  if (law == ElasticLaw::neo_hookean) {
    const double trace_b = NeoHookean::trace_b<D>(F);
    tangent = moduli.bulk_modulus +
              shear_fraction * moduli.shear_modulus * std::pow(J, -2.0 / 3.0) *
                  ((2.0 / 3.0) * largest_squared_stretch<D>(F) + (2.0 / 9.0) * trace_b);
  }
  const double initial_stress = J * cauchy_stress.norm();
  return std::sqrt((tangent + initial_stress) / reference_density);
}

/// The wave speed of particle p of a material with these moduli, law and degradation, from its
/// stored state (the step limit's one call, at the start and after every step).
template <int D>
double particle_wave_speed(const NeoHookean& moduli, ElasticLaw law, Degradation degradation,
                           const Particles<D>& particles, std::size_t p) {
  return longitudinal_wave_speed<D>(moduli, law, particles.F[p], particles.stress[p],
                                    particles.mass[p] / particles.volume0[p],
                                    kept_shear_fraction(degradation, particles.damage[p]));
}

}  // namespace fragmpm::mpm
