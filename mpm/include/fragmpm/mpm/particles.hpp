#pragma once
// Material points as a structure of arrays (docs/design.md). Units SI; in 2D (plane strain) volumes
// are areas per unit thickness [m^2] and masses are per unit thickness [kg/m].
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Removes the entries at `removed` (ascending indices, all below values.size()) and shifts the
/// others down in order. An empty array stays empty (an optional per-particle array).
template <class T>
void erase_entries(std::vector<T>& values, const std::vector<std::size_t>& removed) {
  if (values.empty() || removed.empty()) return;
  std::size_t to = removed.front(), next = 0;
  for (std::size_t from = removed.front(); from < values.size(); ++from) {
    if (next < removed.size() && removed[next] == from) {
      ++next;
      continue;
    }
    values[to++] = values[from];
  }
  values.resize(to);
}

template <int D>
struct Particles {
  std::vector<Vec<D>> x;  ///< position [m]
  std::vector<Vec<D>> v;  ///< velocity [m/s]
  /// C_p [1/s]: the affine part of the velocity field over the particle, v(x) = v_p + C_p (x − x_p)
  /// ([JSS15]). Carried only by the APIC transfer; zero with FLIP.
  std::vector<Mat<D>> affine;
  std::vector<Mat<D>> F;        ///< deformation gradient
  std::vector<double> volume0;  ///< initial volume [m^D per unit thickness^(3-D)]
  std::vector<double> mass;     ///< [kg per unit thickness^(3-D)]
  std::vector<Mat<D>> domain;   ///< CPDI domain: column k is the full edge vector r_(k+1) [m];
                                ///< corners x ± r1/2 ± r2/2
  std::vector<Mat<D>> stress;   ///< Cauchy stress [Pa], in-plane components
  std::vector<double> damage;   ///< d in [0, 1]
  std::vector<double> damage_history;  ///< R: largest equivalent stress seen [Pa]
  std::vector<std::uint8_t> surface;   ///< s in {0, 1}: on a body boundary ([HH17] §2.4)
  std::vector<std::int32_t> body;      ///< body id
  std::vector<std::int32_t> material;  ///< index into the problem's material list
  std::vector<double> strength;        ///< σ_f per particle [Pa]
  std::vector<double> temperature;     ///< θ [K]; empty unless the thermal module runs
  /// F_p⁻¹, the inverse plastic deformation of failed material that flowed (crushed_flow.hpp):
  /// the elastic deformation is F F_p⁻¹. Empty unless a material has crushed_friction_angle.
  std::vector<Mat<D>> plastic_inverse;
  /// The particle's index at step 0. Equal to the index until particles are removed
  /// (`[grid] outside = "remove"`); then frames hold fewer particles, and the id finds each one's
  /// reference configuration in the first frame.
  std::vector<std::int32_t> id;

  std::size_t size() const { return x.size(); }

  /// Resize every per-particle array; temperature only when `thermal` is set. New particles get
  /// id = index.
  void resize(std::size_t n, bool thermal = false) {
    const std::size_t old = id.size();
    x.resize(n, Vec<D>::Zero());
    v.resize(n, Vec<D>::Zero());
    affine.resize(n, Mat<D>::Zero());
    F.resize(n, Mat<D>::Identity());
    volume0.resize(n, 0.0);
    mass.resize(n, 0.0);
    domain.resize(n, Mat<D>::Zero());
    stress.resize(n, Mat<D>::Zero());
    damage.resize(n, 0.0);
    damage_history.resize(n, 0.0);
    surface.resize(n, 0);
    body.resize(n, 0);
    material.resize(n, 0);
    strength.resize(n, 0.0);
    temperature.resize(thermal ? n : 0, 0.0);
    if (!plastic_inverse.empty()) plastic_inverse.resize(n, Mat<D>::Identity());
    id.resize(n);
    for (std::size_t p = old; p < n; ++p) id[p] = static_cast<std::int32_t>(p);
  }

  /// The particles at `rows` (any order, repeats allowed), in that order.
  Particles select(const std::vector<std::size_t>& rows) const {
    Particles out;
    auto gather = [&rows](const auto& from, auto& to) {
      if (from.empty()) return;
      to.resize(rows.size());
      for (std::size_t k = 0; k < rows.size(); ++k) to[k] = from[rows[k]];
    };
    gather(x, out.x);
    gather(v, out.v);
    gather(affine, out.affine);
    gather(F, out.F);
    gather(volume0, out.volume0);
    gather(mass, out.mass);
    gather(domain, out.domain);
    gather(stress, out.stress);
    gather(damage, out.damage);
    gather(damage_history, out.damage_history);
    gather(surface, out.surface);
    gather(body, out.body);
    gather(material, out.material);
    gather(strength, out.strength);
    gather(temperature, out.temperature);
    gather(plastic_inverse, out.plastic_inverse);
    gather(id, out.id);
    return out;
  }

  /// Removes the particles at `removed` (ascending indices) from every array, keeping the order of
  /// the others, so the result does not depend on how the indices were found.
  void erase(const std::vector<std::size_t>& removed) {
    auto compact = [&removed](auto& array) { erase_entries(array, removed); };
    compact(x);
    compact(v);
    compact(affine);
    compact(F);
    compact(volume0);
    compact(mass);
    compact(domain);
    compact(stress);
    compact(damage);
    compact(damage_history);
    compact(surface);
    compact(body);
    compact(material);
    compact(strength);
    compact(temperature);
    compact(plastic_inverse);
    compact(id);
  }
};

}  // namespace fragmpm::mpm
