#pragma once
// Compressible neo-Hookean with the volumetric–isochoric split ([XLS21] eq. (16)-(17)):
//   ψ = U(J) + W(b̄),  U = K/2 (ln J)²,  W = G/2 (tr b̄ − 3),  b̄ = J^{-2/3} F Fᵀ,
//   τ = J ∂ψ/∂F Fᵀ = K ln J I + G dev b̄ (Kirchhoff), σ = τ / J.
// In 2D the deformation is plane strain: F₃₃ = 1, so b₃₃ = 1 enters tr b and dev b̄.
#include <cmath>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

struct NeoHookean {
  double bulk_modulus = 0.0;   ///< K [Pa]
  double shear_modulus = 0.0;  ///< G [Pa]

  /// Trace of b = F Fᵀ including the out-of-plane b₃₃ = 1 in 2D.
  template <int D>
  static double trace_b(const Mat<D>& F) {
    const double in_plane = F.squaredNorm();
    return D == 2 ? in_plane + 1.0 : in_plane;
  }

  /// Kirchhoff stress τ (in-plane block in 2D) [Pa].
  template <int D>
  Mat<D> kirchhoff(const Mat<D>& F) const {
    const double J = F.determinant();
    const double log_J = std::log(J);
    const double J_m23 = std::pow(J, -2.0 / 3.0);
    const Mat<D> b = F * F.transpose();
    const double mean_b = trace_b<D>(F) / 3.0;
    return bulk_modulus * log_J * Mat<D>::Identity() +
           shear_modulus * J_m23 * (b - mean_b * Mat<D>::Identity());
  }

  /// Out-of-plane Kirchhoff stress τ₃₃ of plane strain [Pa].
  double kirchhoff_out_of_plane(const Mat<2>& F) const {
    const double J = F.determinant();
    return bulk_modulus * std::log(J) +
           shear_modulus * std::pow(J, -2.0 / 3.0) * (1.0 - trace_b<2>(F) / 3.0);
  }

  /// Cauchy stress σ = τ / J [Pa].
  template <int D>
  Mat<D> cauchy(const Mat<D>& F) const {
    return kirchhoff<D>(F) / F.determinant();
  }

  /// Strain energy per reference volume ψ [J/m³].
  template <int D>
  double energy_density(const Mat<D>& F) const {
    const double J = F.determinant();
    const double log_J = std::log(J);
    return 0.5 * bulk_modulus * log_J * log_J +
           0.5 * shear_modulus * (std::pow(J, -2.0 / 3.0) * trace_b<D>(F) - 3.0);
  }

  /// Cauchy stress [Pa] and strain energy per reference volume [J/m³] together: the same values as
  /// cauchy() and energy_density(), with J, ln J and J^{-2/3} computed once.
  template <int D>
  void stress_and_energy(const Mat<D>& F, Mat<D>& stress, double& energy) const {
    const double J = F.determinant();
    const double log_J = std::log(J);
    const double J_m23 = std::pow(J, -2.0 / 3.0);
    const double tr_b = trace_b<D>(F);
    const Mat<D> b = F * F.transpose();
    const double mean_b = tr_b / 3.0;
    stress = (bulk_modulus * log_J * Mat<D>::Identity() +
              shear_modulus * J_m23 * (b - mean_b * Mat<D>::Identity())) /
             J;
    energy = 0.5 * bulk_modulus * log_J * log_J + 0.5 * shear_modulus * (J_m23 * tr_b - 3.0);
  }
  /// Dilatational wave speed c = sqrt((K + 4G/3)/ρ) for current density ρ [m/s].
  double wave_speed(double density) const {
    return std::sqrt((bulk_modulus + 4.0 * shear_modulus / 3.0) / density);
  }
};

}  // namespace fragmpm::mpm
