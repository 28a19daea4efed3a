#pragma once
// Material points as a structure of arrays (docs/design.md). Units SI; in 2D (plane strain) volumes
// are areas per unit thickness [m^2] and masses are per unit thickness [kg/m].
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

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

  std::size_t size() const { return x.size(); }

  /// Resize every per-particle array; temperature only when `thermal` is set.
  void resize(std::size_t n, bool thermal = false) {
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
  }
};

}  // namespace fragmpm::mpm
