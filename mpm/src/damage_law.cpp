// Damage laws: Rankine with mesh-regularised linear softening ([XLS21] eq. (19)-(21)), time to
// failure
// ([HH17] eq. (24)), Weibull strengths ([HH17] eq. (25)), stress degradation ([HH17] eq. (26)-(27);
// [XLS21] eq. (7)) and the energy that damage dissipates.
#include "fragmpm/mpm/damage_law.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <stdexcept>

#include "fragmpm/mpm/phase_field.hpp"

namespace fragmpm::mpm {
namespace {

/// H̄ = σ_f² / (2 E G_f) [1/m] ([XLS21] eq. (21)).
double brittleness(double strength, const RankineSoftening& law) {
  return strength * strength / (2.0 * law.youngs_modulus * law.fracture_energy);
}

/// Damage within a few ulps of 1 is 1: the time-to-failure increments Δt/τ are decimal fractions
/// (e.g. 0.1) whose binary sum over τ/Δt steps can fall short of 1 by round-off; without this a
/// particle would need one extra step to fail.
double snap_to_one(double d) {
  return d >= 1.0 - 64.0 * std::numeric_limits<double>::epsilon() ? 1.0 : d;
}

template <int D>
using Eigensolver = Eigen::SelfAdjointEigenSolver<Mat<D>>;

}  // namespace

double rankine_softening_modulus(double strength, const RankineSoftening& law,
                                 double characteristic_length) {
  const double x = brittleness(strength, law) * characteristic_length;  // H̄ l_ch
  if (!(x >= 0.0 && x < 1.0)) return std::numeric_limits<double>::quiet_NaN();
  return x / (1.0 - x);  // [XLS21] eq. (20): H_s = H̄ l_ch / (1 − H̄ l_ch)
}

double rankine_largest_strength(const RankineSoftening& law, double characteristic_length) {
  // H̄ l_ch = σ_f² l_ch / (2 E G_f) < 1  ⇔  σ_f < √(2 E G_f / l_ch).
  return std::sqrt(2.0 * law.youngs_modulus * law.fracture_energy / characteristic_length);
}

double rankine_largest_characteristic_length(double strength, const RankineSoftening& law) {
  // H̄ l_ch < 1  ⇔  l_ch < 1 / H̄ = 2 E G_f / σ_f².
  return 1.0 / brittleness(strength, law);
}

// Plane strain (D = 2): the trial stress holds only the in-plane block. At small strain the
// out-of-plane stress is σ₃₃ = ν (σ₁ + σ₂) with σ₁ ≥ σ₂ the in-plane principal stresses. Whenever
// anything is in tension, σ₁ > 0, and then σ₃₃ − σ₁ = ν σ₂ − (1 − ν) σ₁ ≤ ν σ₁ − (1 − ν) σ₁ =
// (2ν − 1) σ₁ ≤ 0 for ν ≤ ½; when σ₁ ≤ 0 all three are compressive (σ₃₃ ≤ 0). So σ₃₃ never exceeds
// the largest in-plane principal stress while it could reach σ_f > 0, and the in-plane maximum is
// the Rankine equivalent stress ([XLS21] eq. (19)).
template <int D>
double largest_principal_stress(const Mat<D>& stress) {
  if constexpr (D == 2) {
    // Closed form: mean + radius of Mohr's circle.
    const double mean = 0.5 * (stress(0, 0) + stress(1, 1));
    const double half_diff = 0.5 * (stress(0, 0) - stress(1, 1));
    const double shear = 0.5 * (stress(0, 1) + stress(1, 0));
    return mean + std::hypot(half_diff, shear);
  } else {
    Eigensolver<D> es;
    es.computeDirect(stress, Eigen::EigenvaluesOnly);
    return es.eigenvalues().maxCoeff();
  }
}

template <int D>
void update_damage(const DamageLaw& law, const Mat<D>& trial_stress, double strength,
                   double characteristic_length, double dt, double& history, double& damage) {
  if (std::holds_alternative<NoDamage>(law) || std::holds_alternative<PhaseField>(law) ||
      !std::isfinite(strength))
    return;
  update_damage_from_equivalent(law, largest_principal_stress<D>(trial_stress), strength,
                                characteristic_length, dt, history, damage);
}

void update_damage_from_equivalent(const DamageLaw& law, double largest, double strength,
                                   double characteristic_length, double dt, double& history,
                                   double& damage) {
  if (std::holds_alternative<NoDamage>(law) || std::holds_alternative<PhaseField>(law)) return;
  // An infinite (or NaN) strength never fails: such particles keep their history untouched too.
  if (!std::isfinite(strength)) return;
  history = std::max(history, largest);

  if (const auto* rankine = std::get_if<RankineSoftening>(&law)) {
    // A strength above √(2 E G_f / l_ch) has no softening branch (snap-back: H̄ l_ch ≥ 1). The
    // scene refuses it for the nominal strength, but a strong Weibull draw may exceed it. Failing
    // such a particle at its own strength would release σ_f² / (2E) per volume, more than the
    // band's G_f / l_ch; capping its strength at the snap-back limit [BO83] makes it fail at once
    // when σ̄₁ reaches the cap (the limit H_s → ∞ of eq. (20)), releasing exactly G_f / l_ch.
    const double usable =
        std::min(strength, rankine_largest_strength(*rankine, characteristic_length));
    const double R = std::max(usable, history);  // [XLS21] eq. (19)
    if (!(R > usable)) return;
    const double H_s = rankine_softening_modulus(usable, *rankine, characteristic_length);
    double d = 1.0;
    if (std::isfinite(H_s))
      d = std::min(1.0, (1.0 + H_s) * (1.0 - usable / R));  // [XLS21] eq. (20)
    damage = std::max(damage, d);
    return;
  }
  if (const auto* ttf = std::get_if<TimeToFailure>(&law)) {
    // Damage grows only in the steps whose trial stress exceeds σ_f ([HH17] §2.7): a particle that
    // a passing stress peak touched once and that unloaded since keeps the damage it reached.
    if (!(largest >= strength) || damage >= 1.0) return;
    // τ = l_ch / c_f is the time the crack needs to cross the particle ([HH17] §2.7; the paper's
    // "τ = c_f/ℓ" has the ratio inverted, see damage_law.hpp).
    const double tau = characteristic_length / ttf->crack_speed;
    damage = snap_to_one(std::min(1.0, damage + dt / tau));  // [HH17] eq. (24)
  }
}

template <int D>
Mat<D> degrade_stress(const Mat<D>& trial_stress, double damage, Degradation degradation) {
  if (damage <= 0.0) return trial_stress;
  if (degradation == Degradation::isotropic)
    return (1.0 - damage) * trial_stress;  // [XLS21] eq. (7)
  if (degradation == Degradation::volumetric_deviatoric ||
      degradation == Degradation::hencky_spectral)
    throw std::logic_error(
        "degrade_stress: this split is of the energy and needs F (use degrade_with_energy)");
  // 001 eq. (26-27): scale the tensile principal stresses, keep the compressive ones, rebuild with
  // the same eigenvectors.
  Eigensolver<D> es;
  es.computeDirect(trial_stress);
  Vec<D> values = es.eigenvalues();
  for (int i = 0; i < D; ++i)
    if (values[i] > 0.0) values[i] *= 1.0 - damage;
  return es.eigenvectors() * values.asDiagonal() * es.eigenvectors().transpose();
}

// Why Δd ψ_t is the dissipation (docs/design.md: "the energy released must equal what the damage
// law dissipates"). Small strain first: at fixed d the degraded stress is σ = σ̄ − d σ̄⁺ with σ̄ = C ε
// and σ̄⁺ its tensile principal part. Unloading along the ray s ε (s from 1 to 0) keeps the
// principal directions and the signs of σ̄, and σ is linear in s, so the energy given back is
//   ∫₀¹ σ(s ε) : ε ds = ½ σ̄ : ε − d ½ σ̄⁺ : ε = ψ − d ψ_t,   ψ_t = ½ Σ_{σ̄_i > 0} σ̄_i ε_i.
// That recoverable (secant) energy is the stored energy; raising d by Δd at fixed strain releases
// Δd ψ_t, the energy release Y Δd of [XLS21] eq. (6). Along a proportional strain path (uniaxial
// tension, the mode-I loading of a crack band) dψ_t = σ̄⁺ : dε, so the work σ : dε minus the change
// of stored energy is exactly Δd ψ_t at every step. In uniaxial tension σ = (1 − d) E ε with eq.
// (20) falls linearly from σ_f at ε_f = σ_f/E to zero at ε_u = σ_f (1 + H_s) / (E H_s); the
// triangle's area ½ σ_f ε_u = σ_f² / (2 E H̄ l_ch) = G_f / l_ch (because (1 + H_s)/H_s = 1/(H̄ l_ch))
// is the energy dissipated per unit volume, so a band of width l_ch dissipates G_f per unit crack
// area. Finite strain: the same argument with Kirchhoff stress and logarithmic strain ln λ_i (exact
// for a Hencky material, to O(ε) for the neo-Hookean). Isotropic degradation is the special case σ̄⁺
// = σ̄, where (1 − d) ψ is an exact potential and ψ_t = ψ for any path. For non-proportional
// mixed-sign paths ψ_t is the secant estimate of the release.
namespace {

template <int D>
TensileSplit<D> hencky_split(const NeoHookean& model, const Mat<D>& F) {
  const double lambda = model.bulk_modulus - 2.0 * model.shear_modulus / 3.0;
  return hencky_tensile_split<D>(lambda, model.shear_modulus, F);
}

}  // namespace

template <int D>
void elastic_stress_and_energy(const NeoHookean& model, const Mat<D>& F, Degradation degradation,
                               Mat<D>& stress, double& psi, TensileSplit<D>* split_out) {
  if (degradation != Degradation::hencky_spectral) {
    model.stress_and_energy<D>(F, stress, psi);
    return;
  }
  const TensileSplit<D> split = hencky_split<D>(model, F);
  stress = split.tensile_stress + split.compressive_stress;
  psi = split.tensile_energy + split.compressive_energy;
  if (split_out) *split_out = split;
}

template <int D>
DegradedState<D> degrade_hencky(const TensileSplit<D>& split, const Mat<D>& thermal_stress,
                                double J, double damage) {
  // σ = σ⁻ + (1 − d) σ⁺, the derivative of ψ⁻ + (1 − d) ψ⁺ ([KT19] eq. (14)-(16) with the
  // linear degradation of [HH17] eq. (26) in place of g(d)). The thermal pressure acts on the
  // volume and, as U(J) in ψ⁺ or ψ⁻, degrades only in expansion (tr ε = ln J > 0), which
  // coupling_fraction assumes.
  const double volumetric_factor = J > 1.0 ? 1.0 - damage : 1.0;
  return {split.compressive_stress + (1.0 - damage) * split.tensile_stress +
              volumetric_factor * thermal_stress,
          split.tensile_energy};
}

template <int D>
double degradable_energy(const NeoHookean& model, const Mat<D>& F, Degradation degradation) {
  if (degradation == Degradation::isotropic) return model.energy_density<D>(F);
  // ψ_d = ψ⁻ + (1 − d) ψ⁺ gives −∂ψ_d/∂d = ψ⁺ exactly, on any path (no secant estimate).
  if (degradation == Degradation::hencky_spectral) return hencky_split<D>(model, F).tensile_energy;
  if (degradation == Degradation::volumetric_deviatoric) {
    const double log_J = std::log(F.determinant());
    const double volumetric = 0.5 * model.bulk_modulus * log_J * log_J;
    return log_J > 0.0 ? model.energy_density<D>(F) : model.energy_density<D>(F) - volumetric;
  }
  const Mat<D> b = F * F.transpose();
  const Mat<D> tau = model.kirchhoff<D>(F);
  Eigensolver<D> es;
  es.computeDirect(b);
  double psi_t = 0.0;
  for (int i = 0; i < D; ++i) {
    const Vec<D> n = es.eigenvectors().col(i);
    const double tau_i = n.dot(tau * n);  // τ is coaxial with b (isotropic material)
    // ln λ_i = ½ ln(λ_i²); the out-of-plane direction of plane strain has λ₃ = 1 and adds nothing.
    if (tau_i > 0.0) psi_t += 0.25 * tau_i * std::log(es.eigenvalues()[i]);
  }
  return psi_t;
}

template <int D>
DegradedState<D> degrade_with_energy(const NeoHookean& model, const Mat<D>& F,
                                     const Mat<D>& trial_stress, double damage,
                                     Degradation degradation, double psi) {
  if (degradation == Degradation::isotropic)
    return {(1.0 - damage) * trial_stress, psi};  // [XLS21] eq. (7)
  if (degradation == Degradation::volumetric_deviatoric) {
    // [AMM09]'s split on the neo-Hookean of [XLS21] eq. (16)-(17): ψ_d = U·[J ≤ 1] + (1 − d)(W +
    // U·[J > 1]). Its Kirchhoff stress is K ln J I times (1 − d) only in expansion, plus (1 − d) G
    // dev b̄: the two terms of model.kirchhoff, scaled apart. The thermal pressure (the rest of
    // the trial stress, isotropic) acts on the volume and is scaled with the volumetric term.
    const double J = F.determinant();
    const double log_J = std::log(J);
    const double volumetric_factor = log_J > 0.0 ? 1.0 - damage : 1.0;
    const Mat<D> tau = model.kirchhoff<D>(F);
    const double tau_volumetric = model.bulk_modulus * log_J;
    const Mat<D> tau_deviatoric = tau - tau_volumetric * Mat<D>::Identity();
    const Mat<D> thermal = trial_stress - tau / J;
    const Mat<D> stress = (volumetric_factor * tau_volumetric * Mat<D>::Identity() +
                           (1.0 - damage) * tau_deviatoric) /
                              J +
                          volumetric_factor * thermal;
    const double volumetric_energy = 0.5 * model.bulk_modulus * log_J * log_J;
    return {stress, log_J > 0.0 ? psi : psi - volumetric_energy};
  }
  if (degradation == Degradation::hencky_spectral) {
    const TensileSplit<D> split = hencky_split<D>(model, F);
    return degrade_hencky<D>(split, trial_stress - split.tensile_stress - split.compressive_stress,
                             F.determinant(), damage);
  }
  const Mat<D> b = F * F.transpose();
  const Mat<D> tau = model.kirchhoff<D>(F);
  Eigensolver<D> es;
  es.computeDirect(b);
  DegradedState<D> out{trial_stress, 0.0};
  for (int i = 0; i < D; ++i) {
    const Vec<D> n = es.eigenvectors().col(i);
    const double sigma_i = n.dot(trial_stress * n);
    if (sigma_i > 0.0) out.stress -= (damage * sigma_i) * (n * n.transpose());
    const double tau_i = n.dot(tau * n);
    if (tau_i > 0.0) out.degradable += 0.25 * tau_i * std::log(es.eigenvalues()[i]);
  }
  return out;
}

double weibull_median_strength(double volume, const WeibullStrength& w, int dimension) {
  const double V = dimension == 2 ? volume * w.thickness : volume;
  return w.reference_strength * std::pow(w.reference_volume / V, 1.0 / w.modulus);
}

std::vector<double> weibull_strengths(const std::vector<double>& volumes, const WeibullStrength& w,
                                      int dimension) {
  std::mt19937_64 rng(w.seed);
  std::vector<double> out(volumes.size());
  const double ln_half = std::log(0.5);
  for (std::size_t p = 0; p < volumes.size(); ++p) {
    // ℛ uniform in the open interval (0, 1) from the top 53 bits: the mid-points (k + ½) 2⁻⁵³ never
    // give ln ℛ = 0 or −∞, and the mapping is the same on every standard library (unlike
    // std::uniform_real_distribution).
    const double R = (static_cast<double>(rng() >> 11) + 0.5) * 0x1p-53;
    const double V = dimension == 2 ? volumes[p] * w.thickness : volumes[p];
    out[p] = w.reference_strength * std::pow(w.reference_volume / V * std::log(R) / ln_half,
                                             1.0 / w.modulus);  // [HH17] eq. (25)
  }
  return out;
}

template double largest_principal_stress<2>(const Mat<2>&);
template double largest_principal_stress<3>(const Mat<3>&);
template void update_damage<2>(const DamageLaw&, const Mat<2>&, double, double, double, double&,
                               double&);
template void update_damage<3>(const DamageLaw&, const Mat<3>&, double, double, double, double&,
                               double&);
template Mat<2> degrade_stress<2>(const Mat<2>&, double, Degradation);
template Mat<3> degrade_stress<3>(const Mat<3>&, double, Degradation);
template void elastic_stress_and_energy<2>(const NeoHookean&, const Mat<2>&, Degradation, Mat<2>&,
                                           double&, TensileSplit<2>*);
template void elastic_stress_and_energy<3>(const NeoHookean&, const Mat<3>&, Degradation, Mat<3>&,
                                           double&, TensileSplit<3>*);
template DegradedState<2> degrade_hencky<2>(const TensileSplit<2>&, const Mat<2>&, double, double);
template DegradedState<3> degrade_hencky<3>(const TensileSplit<3>&, const Mat<3>&, double, double);
template double degradable_energy<2>(const NeoHookean&, const Mat<2>&, Degradation);
template double degradable_energy<3>(const NeoHookean&, const Mat<3>&, Degradation);
template DegradedState<2> degrade_with_energy<2>(const NeoHookean&, const Mat<2>&, const Mat<2>&,
                                                 double, Degradation, double);
template DegradedState<3> degrade_with_energy<3>(const NeoHookean&, const Mat<3>&, const Mat<3>&,
                                                 double, Degradation, double);

}  // namespace fragmpm::mpm
