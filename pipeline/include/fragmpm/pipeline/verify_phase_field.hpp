#pragma once
// `fragmpm verify phase-field-bar` (docs/verification.md): closed-form checks of the AT2 phase
// field
// ([KT19]) — the profile of an imposed crack, and the crack energy of a bar pulled apart.
#include <optional>
#include <string>
#include <vector>

#include "fragmpm/mpm/phase_field.hpp"
#include "fragmpm/pipeline/verify.hpp"

namespace fragmpm::pipeline {

/// The scene of a strip [−a, a] × [0, height] [m] of one phase-field material (l₀ = 1 mm,
/// G_c = 100 J/m², E = 10 GPa, ν = 0, no load, one step) with 2 particles per cell of size
/// `cell_size` [m]: the particle lattice has spacing s = h/2 and a column on x = 0, the outermost
/// columns stand at x = ±n s (n = `columns_each_side`) and the body ends half a spacing beyond
/// them, a = (n + ½) s; the grid reaches 4 cells past the body on every side. `shape`: a [grid]
/// shape_function name; `material_extra`: TOML lines added to the material (e.g. an anisotropy).
/// The scene of the imposed-crack checks below and of the phase-field solver's tests.
std::string phase_field_strip_scene(double cell_size, const std::string& shape,
                                    int columns_each_side, double height,
                                    const std::string& material_extra = "");

/// An imposed straight crack on a strip (l₀ = 1 mm, G_c = 100 J/m², 2 particles per cell): the
/// particle column at x = 0 carries a history 10⁸ G_c/(4 l₀), the phase field is solved once, and
/// the particles' d is compared with d = cosh((a − |x|)/(2 l₀)) / cosh(a/(2 l₀)), the solution
/// of [KT19] eq. (20) with d(0) = 1 and no flux at the strip's ends x = ±a (a ≈ 10 l₀; the
/// exp(−|x|/(2 l₀)) of an infinite bar to 10⁻⁴).
struct CrackProfile {
  double max_error = 0.0;     ///< largest |d − d_exact| over the particles
  double rms_error = 0.0;     ///< root mean square of d − d_exact over the particles
  double energy_ratio = 0.0;  ///< Ψ_f / (G_c × strip height)
  long long particles = 0;
  double wall_seconds = 0.0;
};

/// `shape`: a [grid] shape_function name. With `anisotropy` (the B-spline only) the material has
/// the fourth-order term of [KT19] §2.2 and the strip is [−20 l₀, 20 l₀] and 10 and 20 l₀ high:
/// the crack's normal is x, at ψ = −φ from the material axis ξ₁, and the oracle is the closed form
/// of mpm::phase_field_straight_crack_profile / _energy for γ_n = phase_field_normal_gamma(−φ):
/// the profile within 2 l₀ of the taller strip's middle, the energy per crack length from the
/// difference of the two heights, over Ḡ_c × that energy.
CrackProfile phase_field_crack_profile(
    double cell_size, const std::string& shape,
    const std::optional<mpm::PhaseFieldAnisotropy>& anisotropy = std::nullopt);

/// One level of the pulled bar (scenes/verify/phase-field-bar.toml): `variant` "seeded" (a partial
/// crack, d ≈ ½, imposed at mid-length by a history G_c / s on one particle column; grips at
/// 0.5 m/s; partitioned), "seeded-one-field" (the same with partitioning off) or "unseeded" (no
/// imperfection, grips at 1 m/s). Rows: crack energy / (G_c × height) (with the 5 % target for
/// "seeded"), the bulk's share of it, and the balance error / input. std::invalid_argument for an
/// unknown variant.
std::vector<VerifyRow> phase_field_bar_level(const std::string& variant, int level,
                                             double cell_size);

}  // namespace fragmpm::pipeline
