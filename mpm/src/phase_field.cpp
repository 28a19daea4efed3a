// The spectral tension–compression split of a phase-field material ([KT19] eq. (14)) in the
// principal logarithmic strains.
#include "fragmpm/mpm/phase_field.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

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

template TensileSplit<2> hencky_tensile_split<2>(double, double, const Mat<2>&);
template TensileSplit<3> hencky_tensile_split<3>(double, double, const Mat<3>&);

}  // namespace fragmpm::mpm
