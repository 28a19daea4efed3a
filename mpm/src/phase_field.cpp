// The spectral tension–compression split of a phase-field material ([KT19] eq. (14)) in the
// principal logarithmic strains.
#include "fragmpm/mpm/phase_field.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>

namespace fragmpm::mpm {

template <int D>
TensileSplit<D> hencky_tensile_split(double lambda, double shear_modulus, const Mat<D>& F) {
  const Mat<D> b = F * F.transpose();
  Eigen::SelfAdjointEigenSolver<Mat<D>> es;
  es.computeDirect(b);
  Vec<D> strain;  // principal logarithmic strains ln λ_i = ½ ln(eigenvalue of b)
  for (int i = 0; i < D; ++i) strain[i] = 0.5 * std::log(es.eigenvalues()[i]);
  const double trace = strain.sum();
  const double trace_plus = std::max(trace, 0.0), trace_minus = std::min(trace, 0.0);
  TensileSplit<D> out;
  out.tensile_energy = 0.5 * lambda * trace_plus * trace_plus;
  out.compressive_energy = 0.5 * lambda * trace_minus * trace_minus;
  Vec<D> tau_plus, tau_minus;  // principal Kirchhoff stresses of each part
  for (int i = 0; i < D; ++i) {
    const double plus = std::max(strain[i], 0.0), minus = std::min(strain[i], 0.0);
    out.tensile_energy += shear_modulus * plus * plus;
    out.compressive_energy += shear_modulus * minus * minus;
    tau_plus[i] = lambda * trace_plus + 2.0 * shear_modulus * plus;
    tau_minus[i] = lambda * trace_minus + 2.0 * shear_modulus * minus;
  }
  const double inverse_J = 1.0 / F.determinant();
  const Mat<D>& n = es.eigenvectors();
  out.tensile_stress = inverse_J * (n * tau_plus.asDiagonal() * n.transpose());
  out.compressive_stress = inverse_J * (n * tau_minus.asDiagonal() * n.transpose());
  return out;
}

Eigen::Matrix3d phase_field_anisotropy_global(const PhaseFieldAnisotropy& a) {
  Eigen::Matrix3d gamma;
  gamma << a.gamma_1111, a.gamma_1122, 0.0, a.gamma_1122, a.gamma_2222, 0.0, 0.0, 0.0, a.gamma_1212;
  const double c = std::cos(a.orientation), s = std::sin(a.orientation);
  // Rows: the material-axis Hessian entries ξ₁ᵀHξ₁, ξ₂ᵀHξ₂, ξ₁ᵀHξ₂ in terms of (H_xx, H_yy, H_xy).
  Eigen::Matrix3d T;
  T << c * c, s * s, 2.0 * c * s, s * s, c * c, -2.0 * c * s, -c * s, c * s, c * c - s * s;
  return T.transpose() * gamma * T;
}

double phase_field_normal_gamma(const PhaseFieldAnisotropy& a, double psi) {
  const double c = std::cos(psi), s = std::sin(psi);
  return a.gamma_1111 * c * c * c * c + a.gamma_2222 * s * s * s * s +
         (2.0 * a.gamma_1122 + a.gamma_1212) * c * c * s * s;
}

namespace {

/// The decaying roots r₁, r₂ (positive real part) of γ r⁴ − r² + ¼ = 0, lengths in l₀.
void straight_crack_roots(double gamma, std::complex<double>& r1, std::complex<double>& r2) {
  using C = std::complex<double>;
  const C root = std::sqrt(C(1.0 - gamma, 0.0));
  r1 = std::sqrt((1.0 + root) / (2.0 * gamma));
  r2 = std::sqrt((1.0 - root) / (2.0 * gamma));
  if (r1.real() < 0.0) r1 = -r1;
  if (r2.real() < 0.0) r2 = -r2;
}

bool double_root(const std::complex<double>& r1, const std::complex<double>& r2) {
  return std::abs(r1 - r2) < 1e-7 * std::abs(r1);
}

}  // namespace

double phase_field_straight_crack_profile(double gamma, double distance) {
  const double xi = std::abs(distance);
  if (!(gamma > 0.0)) return std::exp(-0.5 * xi);
  std::complex<double> r1, r2;
  straight_crack_roots(gamma, r1, r2);
  if (double_root(r1, r2)) {
    const double r = r1.real();
    return (1.0 + r * xi) * std::exp(-r * xi);
  }
  const std::complex<double> A = r2 / (r2 - r1), B = -r1 / (r2 - r1);
  return (A * std::exp(-r1 * xi) + B * std::exp(-r2 * xi)).real();
}

double phase_field_straight_crack_energy(double gamma) {
  if (!(gamma > 0.0)) return 1.0;  // second order: e^(−|x|/(2 l₀)), G_c exactly
  std::complex<double> r1, r2;
  straight_crack_roots(gamma, r1, r2);
  double third;  // the third derivative at the crack of one side's profile
  if (double_root(r1, r2)) {
    // γ = 1: a double root r, d = (1 + r x) e^(−r x), whose third derivative at 0 is 2 r³.
    third = 2.0 * std::pow(r1.real(), 3);
  } else {
    // d = A e^(−r₁x) + B e^(−r₂x) with A + B = 1 and r₁A + r₂B = 0 (d'(0) = 0); for γ > 1 the
    // roots are a conjugate pair and d is real.
    const std::complex<double> A = r2 / (r2 - r1), B = -r1 / (r2 - r1);
    third = (-(A * r1 * r1 * r1 + B * r2 * r2 * r2)).real();
  }
  return 2.0 * gamma * third;
}

template TensileSplit<2> hencky_tensile_split<2>(double, double, const Mat<2>&);
template TensileSplit<3> hencky_tensile_split<3>(double, double, const Mat<3>&);

}  // namespace fragmpm::mpm
