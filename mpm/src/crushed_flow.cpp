// The frictional return of failed material (crushed_flow.hpp).
//
// Why neither the plastic work nor the released energy is negative: along the return
// ε_i(s) = m + s e_i with Σ e_i = 0 (in 2D over the in-plane strains), tr ε is fixed, and with
// τ_i = λ ⟨tr ε⟩₋ + 2μ ⟨ε_i⟩₋ the plastic work is Σ τ_i(s) (1 − s) e_i = 2μ (1 − s) Σ ⟨ε_i(s)⟩₋ e_i
// (the pressure term drops), while d/ds ψ⁻ = 2μ Σ ⟨ε_i(s)⟩₋ e_i, so ψ⁻(1) − ψ⁻(s) ≥ 0 for s ≤ 1
// too when that sum is never negative. The sum
// Σ_{ε_i < 0} e_i (m + s e_i) is never negative: for m ≥ 0 a negative ε_i needs e_i < 0, a product
// of two negatives; for m < 0 the full sum is s Σ e_i² ≥ 0 and the excluded terms (ε_i ≥ 0 needs
// e_i > 0) are e_i ε_i ≥ 0, so the restricted sum is s Σ_{ε_i<0} e_i² − m Σ_{ε_i ≥ 0} e_i ≥ 0.
#include "fragmpm/mpm/crushed_flow.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace fragmpm::mpm {

namespace {
inline double negative_part(double x) {
  return x < 0.0 ? x : 0.0;
}

/// ψ⁻ = λ/2 ⟨tr ε⟩₋² + μ Σ ⟨ε_i⟩₋² ([KT19] eq. (14)) from the principal logarithmic strains.
template <int D>
double compressive_energy(const Vec<D>& log_strains, double lambda, double shear_modulus) {
  const double volumetric = negative_part(log_strains.sum());
  double energy = 0.5 * lambda * volumetric * volumetric;
  for (int i = 0; i < D; ++i)
    energy += shear_modulus * negative_part(log_strains[i]) * negative_part(log_strains[i]);
  return energy;
}
}  // namespace

template <int D>
double crushed_yield_function(const Vec<D>& log_strains, double lambda, double shear_modulus,
                              double sin_friction) {
  const double volumetric = negative_part(log_strains.sum());
  Vec<D> tau;
  for (int i = 0; i < D; ++i)
    tau[i] = lambda * volumetric + 2.0 * shear_modulus * negative_part(log_strains[i]);
  if constexpr (D == 2) {
    // In-plane Mohr–Coulomb: radius of the in-plane Mohr circle against sin φ times its centre's
    // compression.
    const double largest = tau.maxCoeff(), smallest = tau.minCoeff();
    return 0.5 * (largest - smallest) + sin_friction * 0.5 * (largest + smallest);
  } else {
    const double mean = tau.sum() / 3.0;
    const double deviator_norm = (tau.array() - mean).matrix().norm();  // |s| = √(2 J₂)
    const double cone_slope = 6.0 * sin_friction / (3.0 - sin_friction);
    return std::sqrt(1.5) * deviator_norm + cone_slope * mean;  // √(3 J₂) − M p, p = −mean
  }
}

template <int D>
CrushedFlowReturn<D> crushed_flow_return(const Mat<D>& elastic_F, double lambda,
                                         double shear_modulus, double sin_friction) {
  CrushedFlowReturn<D> result;
  const Eigen::SelfAdjointEigenSolver<Mat<D>> eigen(elastic_F * elastic_F.transpose());
  const Vec<D> log_strains = 0.5 * eigen.eigenvalues().array().log().matrix();
  const double mean = log_strains.mean();
  const Vec<D> deviator = (log_strains.array() - mean).matrix();
  auto yield_at = [&](double s) {
    const Vec<D> scaled = (deviator * s).array() + mean;
    return crushed_yield_function<D>(scaled, lambda, shear_modulus, sin_friction);
  };
  // The stress scale of f: a relative tolerance on it absorbs round-off in an admissible state.
  const double stress_scale = (lambda + 2.0 * shear_modulus) * log_strains.cwiseAbs().maxCoeff();
  if (yield_at(1.0) <= 1e-12 * stress_scale) return result;
  double admissible = 0.0, excessive = 1.0;
  // f(0) ≤ 0: at s = 0 the state is hydrostatic (f = sin φ · (mean stress) ≤ 0) or stress-free.
  for (int iteration = 0; iteration < 60 && excessive - admissible > 1e-15; ++iteration) {
    const double middle = 0.5 * (admissible + excessive);
    (yield_at(middle) <= 0.0 ? admissible : excessive) = middle;
  }
  result.deviator_scale = admissible;
  result.flowed = true;
  const Vec<D> returned = (deviator * admissible).array() + mean;
  result.released = compressive_energy<D>(log_strains, lambda, shear_modulus) -
                    compressive_energy<D>(returned, lambda, shear_modulus);
  const double volumetric = negative_part(returned.sum());
  for (int i = 0; i < D; ++i) {
    const double tau = lambda * volumetric + 2.0 * shear_modulus * negative_part(returned[i]);
    result.plastic_work += tau * (1.0 - admissible) * deviator[i];
  }
  // ε_i^new − ε_i = (s − 1) e_i along each principal direction n_i of b_e.
  const Vec<D> stretch_factors = ((admissible - 1.0) * deviator).array().exp().matrix();
  result.correction =
      eigen.eigenvectors() * stretch_factors.asDiagonal() * eigen.eigenvectors().transpose();
  return result;
}

template double crushed_yield_function<2>(const Vec<2>&, double, double, double);
template double crushed_yield_function<3>(const Vec<3>&, double, double, double);
template CrushedFlowReturn<2> crushed_flow_return<2>(const Mat<2>&, double, double, double);
template CrushedFlowReturn<3> crushed_flow_return<3>(const Mat<3>&, double, double, double);

}  // namespace fragmpm::mpm
