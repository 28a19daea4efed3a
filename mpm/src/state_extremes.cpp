#include "fragmpm/mpm/state_extremes.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <cstdio>

namespace fragmpm::mpm {

template <int D>
StateExtremes state_extremes(const Particles<D>& P) {
  StateExtremes out;
  for (std::size_t p = 0; p < P.size(); ++p) {
    const double J = P.F[p].determinant();
    if (out.largest_J_particle < 0 || J > out.largest_J) {
      out.largest_J = J;
      out.largest_J_particle = static_cast<long long>(p);
    }
    if (J > swollen_volume_ratio) ++out.swollen;
    // The stored stress is symmetric; its symmetric part guards against round-off asymmetry.
    const Mat<D> symmetric = 0.5 * (P.stress[p] + P.stress[p].transpose());
    const double largest = Eigen::SelfAdjointEigenSolver<Mat<D>>(symmetric, Eigen::EigenvaluesOnly)
                               .eigenvalues()
                               .cwiseAbs()
                               .maxCoeff();
    if (out.largest_stress_particle < 0 || largest > out.largest_stress) {
      out.largest_stress = largest;
      out.largest_stress_particle = static_cast<long long>(p);
    }
  }
  return out;
}

std::string describe(const StateExtremes& e) {
  if (e.largest_J_particle < 0) return "no particles";
  char text[256];
  std::snprintf(text, sizeof text,
                "largest J = det F %.6g (particle %lld), %zu particle%s with J > %g, largest "
                "|principal stress| %.4g MPa (particle %lld)",
                e.largest_J, e.largest_J_particle, e.swollen, e.swollen == 1 ? "" : "s",
                swollen_volume_ratio, e.largest_stress * 1e-6, e.largest_stress_particle);
  return text;
}

template StateExtremes state_extremes<2>(const Particles<2>&);
template StateExtremes state_extremes<3>(const Particles<3>&);

}  // namespace fragmpm::mpm
