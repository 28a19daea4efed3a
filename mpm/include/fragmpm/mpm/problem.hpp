#pragma once
// The compiled scene: everything the solver needs, already in SI units and validated.
// The scene-file parser (pipeline/) fills this; the core never sees TOML or units.
#include <limits>
#include <string>
#include <vector>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/velocity_history.hpp"

namespace fragmpm::mpm {

enum class ShapeFunctionKind { linear, ugimp, cpdi };

/// Compressible neo-Hookean (000 eq. 16-17), given by bulk and shear modulus.
struct MaterialSpec {
  std::string name;
  double bulk_modulus = 0.0;   ///< K [Pa]
  double shear_modulus = 0.0;  ///< G [Pa]
  double density = 0.0;        ///< ρ0 [kg/m^3]
};

/// contact: one-sided, frictional (Coulomb μ = friction); roller: bilateral normal constraint, free
/// tangentially; fixed: the material moves with the wall.
enum class WallKind { contact, roller, fixed };

/// A rigid plane through `point` (at t = 0) with unit `normal` pointing into the material side.
template <int D>
struct WallSpec {
  std::string name;
  Vec<D> point = Vec<D>::Zero();   ///< [m]
  Vec<D> normal = Vec<D>::Zero();  ///< unit
  WallKind kind = WallKind::contact;
  double friction = 0.0;           ///< Coulomb coefficient μ
  VelocityHistory<D> velocity;
};

template <int D>
struct GridSpec {
  double cell_size = 0.0;           ///< h [m]
  Vec<D> min = Vec<D>::Zero();      ///< lower corner of the computational domain [m]
  Vec<D> max = Vec<D>::Zero();      ///< upper corner [m]
  ShapeFunctionKind shape_function = ShapeFunctionKind::cpdi;
};

struct TimeSpec {
  double cfl = 0.4;           ///< C_cfl in Δt = C h / max(c + |v|)
  double fixed_dt = 0.0;      ///< [s]; 0 = adaptive
  double pic_fraction = 0.0;  ///< ζ of 000 eq. (64): 0 = pure FLIP, 1 = pure PIC
};

struct StopSpec {
  double end_time = std::numeric_limits<double>::infinity();   ///< [s]
  long long max_steps = std::numeric_limits<long long>::max();
  double platen_displacement = std::numeric_limits<double>::infinity();  ///< |displacement| [m]
  int platen = -1;  ///< wall index whose displacement is watched; -1 = none
};

struct OutputSpec {
  double interval = 0.0;        ///< [s] between frames; 0 = only first and last
  std::vector<std::string> fields;  ///< frame datasets to write (empty = all)
};

template <int D>
struct Problem {
  GridSpec<D> grid;
  TimeSpec time;
  StopSpec stop;
  OutputSpec output;
  Vec<D> gravity = Vec<D>::Zero();  ///< [m/s^2]
  std::vector<MaterialSpec> materials;
  std::vector<WallSpec<D>> walls;
  std::vector<std::string> body_names;  ///< index = body id
  Particles<D> particles;
  std::string scene_path;   ///< where it came from (for messages and /meta)
  std::string scene_text;   ///< verbatim scene file, stored in /meta so a run can be restarted
};

}  // namespace fragmpm::mpm
