#pragma once
// The AT2 phase field of [KT19] as a damage law: the material law of one particle (degradation,
// tension–compression split, history field) and the coefficients of the nodal phase-field
// equation. The grid solve is the phase-field stage (mpm/src/step/phase_field_stage.cpp).
//
// Damage d here is the paper's 1 − c (c = 1 intact, c = 0 cracked), so d plays the role of the
// other laws' damage in partitioning, fragments, frames and figures. With d for 1 − c, [KT19]
// eq. (20) (isotropic, γ = 0) times G_c/(4 l₀) reads
//   (G_c/(4 l₀) + (1 − k_f) H) d − G_c l₀ Δd = (1 − k_f) H,
// and its crack density (eq. (3)-(4)) is G_c (d²/(4 l₀) + l₀ |∇d|²). The length l₀ is the paper's:
// a straight crack has the profile d = exp(−|x|/(2 l₀)) (d'' = d/(4 l₀²) away from it), whose
// energy is G_c per unit crack area. Conventions that write the density d²/(2ℓ) + ℓ/2 |∇d|² use
// ℓ = 2 l₀ and the profile exp(−|x|/ℓ).
#include <Eigen/Dense>
#include <algorithm>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// The fourth-order anisotropic crack density of [KT19] §2.2 (eq. (4)-(6)), two-dimensional:
/// G_c l₀³ χᵀ Γ χ is added to the density, with χ = (∂²d/∂ξ₁², ∂²d/∂ξ₂², ∂²d/∂ξ₁∂ξ₂) the second
/// derivatives in the material axes ξ and Γ = [[γ₁₁₁₁, γ₁₁₂₂, 0], [γ₁₁₂₂, γ₂₂₂₂, 0], [0, 0, γ₁₂₁₂]]
/// (eq. (6), orthotropic in the material axes). Written this way, with the mixed derivative
/// counted once, the paper's parameters give its surface energies: cubic (1, 1, 0, 74) with
/// Ḡ_c = 0.002121 N/mm has G_c(θ) from 0.0030 to 0.0049 N/mm, orthotropic (1, 80, 0, 74) up to
/// 0.0067 N/mm ([KT19] §5.1; phase_field_straight_crack_energy).
struct PhaseFieldAnisotropy {
  double gamma_1111 = 0.0, gamma_2222 = 0.0, gamma_1122 = 0.0, gamma_1212 = 0.0;
  double orientation = 0.0;  ///< φ: material axis ξ₁ from the x axis, counter-clockwise [rad]
};

/// AT2 phase field with the history field ([KT19] §2.1, eq. (14)-(15), (20), (47)-(57)).
struct PhaseField {
  double length_scale = 0.0;        ///< l₀ [m] ([KT19] eq. (4))
  double fracture_energy = 0.0;     ///< G_c [J/m²] (Ḡ_c with anisotropy)
  double residual_stiffness = 0.0;  ///< k_f of g = (1 − k_f)(1 − d)² + k_f ([KT19] eq. (15))
  bool anisotropic = false;         ///< the fourth-order term of `anisotropy` is on
  PhaseFieldAnisotropy anisotropy;
};

/// Γ in the global axes, Γ_g = Tᵀ Γ T: the density χᵀ Γ χ in material axes equals χ_gᵀ Γ_g χ_g with
/// χ_g = (∂²d/∂x², ∂²d/∂y², ∂²d/∂x∂y), since the material-axis Hessian is Rᵀ H R (R's columns the
/// axes ξ₁ = (cos φ, sin φ), ξ₂ = (−sin φ, cos φ)), which is χ = T χ_g.
Eigen::Matrix3d phase_field_anisotropy_global(const PhaseFieldAnisotropy& anisotropy);

/// γ_n = χ(n)ᵀ Γ χ(n) / d''² for a field d(n·x) whose normal n makes the angle ψ with ξ₁:
/// γ₁₁₁₁ cos⁴ψ + γ₂₂₂₂ sin⁴ψ + (2 γ₁₁₂₂ + γ₁₂₁₂) cos²ψ sin²ψ.
double phase_field_normal_gamma(const PhaseFieldAnisotropy& anisotropy, double psi);

/// Energy per unit area of a straight crack, over G_c, when the density across it is
/// d²/(4 l₀) + l₀ d'² + l₀³ γ_n d''² ([KT19] eq. (8) in closed form): the minimiser with d(0) = 1
/// solves γ_n d'''' − d'' + d/4 = 0 (lengths in l₀) on each side, decaying, with d'(0) = 0 when
/// γ_n > 0, and the energy of each side is γ_n d'''(0) (by parts, with the equation). 1 for
/// γ_n = 0 (the profile e^(−|x|/(2 l₀))), √2 for γ_n = 1 (profile (1 + u) e^(−u), u = |x|/(√2 l₀)).
double phase_field_straight_crack_energy(double gamma_normal);

/// d at `distance` (in units of l₀) from that straight crack: the minimiser above, e^(−|x|/2) for
/// γ_n = 0.
double phase_field_straight_crack_profile(double gamma_normal, double distance);

/// Default D_cr of [contact] in a scene with a phase-field material: the AT2 field approaches
/// d = 1 only as the history grows without bound (phase_field_uniform_damage), so the default 1 of
/// the other laws would never let a phase-field crack become separable. d ≥ 0.95 needs
/// (1 − k_f) H ≥ 19 G_c/(4 l₀), which the particles of an opening crack pass at once.
inline constexpr double phase_field_critical_damage = 0.95;

/// g(d) = (1 − k_f)(1 − d)² + k_f ([KT19] eq. (15) with c = 1 − d).
inline double phase_field_degradation(double damage, double residual_stiffness) {
  const double c = 1.0 - damage;
  return (1.0 - residual_stiffness) * c * c + residual_stiffness;
}

/// Crack density per unit volume G_c (d²/(4 l₀) + l₀ |∇d|²) [J/m³] ([KT19] eq. (3)-(4), γ = 0).
template <int D>
inline double phase_field_crack_density(const PhaseField& law, double damage,
                                        const Vec<D>& gradient) {
  const double l0 = law.length_scale;
  return law.fracture_energy * (damage * damage / (4.0 * l0) + l0 * gradient.squaredNorm());
}

/// d of a uniform history field H [J/m³] (no gradient): the pointwise solution of the equation
/// above, (1 − k_f) H / (G_c/(4 l₀) + (1 − k_f) H).
inline double phase_field_uniform_damage(const PhaseField& law, double history) {
  const double drive = (1.0 - law.residual_stiffness) * history;
  return drive / (law.fracture_energy / (4.0 * law.length_scale) + drive);
}

/// The tension–compression split of the elastic energy of a phase-field material, ψ = g ψ⁺ + ψ⁻,
/// and the matching Cauchy stresses σ = g σ⁺ + σ⁻.
template <int D>
struct TensileSplit {
  Mat<D> tensile_stress = Mat<D>::Zero();      ///< σ⁺ [Pa]
  Mat<D> compressive_stress = Mat<D>::Zero();  ///< σ⁻ [Pa]
  double tensile_energy = 0.0;                 ///< ψ⁺ per reference volume [J/m³]
  double compressive_energy = 0.0;             ///< ψ⁻ per reference volume [J/m³]
};

/// The spectral split of [KT19] eq. (14) (Miehe's: ψ± = λ/2 ⟨tr ε⟩±² + μ Σ ⟨ε_i⟩±², ⟨x⟩± the
/// positive / negative part) written in the principal logarithmic strains ε_i = ln λ_i of
/// b = F Fᵀ. This Hencky form is an exact potential at finite strain: the Kirchhoff stress of an
/// isotropic function of the logarithmic strain is its derivative, τ± = Σ_i (λ ⟨tr ε⟩± +
/// 2μ ⟨ε_i⟩±) n_i ⊗ n_i, σ± = τ± / J, so σ = g σ⁺ + σ⁻ is the derivative of g ψ⁺ + ψ⁻ at fixed d.
/// At small strain ε_i are the principal strains and the split is the paper's. Plane strain
/// (D = 2): the out-of-plane logarithmic strain is 0 and adds nothing to either part. `lambda` and
/// `shear_modulus` μ are the Lamé constants [Pa] (λ = K − 2G/3, μ = G).
template <int D>
TensileSplit<D> hencky_tensile_split(double lambda, double shear_modulus, const Mat<D>& F);

}  // namespace fragmpm::mpm
