#pragma once
// V5 Hertz line contact (docs/verification.md, `hertz`; [XLS21] §4.1, eq. (88)-(89)): the closed
// form, and one relaxed level with its measured contact pressure.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

namespace fragmpm::pipeline {

/// Hertz's solution for a cylinder of radius R pressed on a rigid flat by a line load F (per unit
/// length), plane strain ([XLS21] eq. (88)-(89); K. L. Johnson, Contact Mechanics, §4.3).
///
/// Derivation. Two bodies whose gap near the first touch is g(x) = x² / (2R), 1/R = 1/R₁ + 1/R₂,
/// pressed together by F: each surface is a half-plane loaded by p(x) on |x| < b, whose normal
/// displacement gradient is du/dx = −(2(1 − ν²)/(π E)) ∫ p(s) / (x − s) ds. Contact closes the
/// gap, so the two gradients add up to x / R inside the contact:
///   (1/π) ∫ p(s) / (x − s) ds = (E′ / (4R)) x,  2/E′ = (1 − ν₁²)/E₁ + (1 − ν₂²)/E₂,
/// with E′ as [XLS21] defines it below eq. (88). The solution bounded at x = ±b is
/// p(x) = p_max √(1 − x²/b²) (eq. (89)) with p_max = E′ b / (4R); F = ∫ p = π p_max b / 2 then
/// gives b = 2 √(2 F R / (π E′)) and p_max = 2F / (π b) (eq. (88)). A rigid flat (E₂ → ∞) has
/// E′ = 2E / (1 − ν²), twice the plane-strain modulus E / (1 − ν²): b = 2 √(F R (1 − ν²)/(π E)),
/// Johnson's a² = 4 P R / (π E*) with E* = E / (1 − ν²). (Putting E′ = E / (1 − ν²) into eq. (88)
/// would give a contact √2 wider.) For R = 4 mm, E = 10 GPa, ν = 0, F = 156.7 N/mm:
/// b = 0.2825 mm, p_max = 353.1 MPa.
struct HertzOracle {
  double load = 156.7e3;         ///< F [N/m]
  double radius = 4e-3;          ///< R [m]
  double youngs_modulus = 10e9;  ///< E [Pa]
  double poisson_ratio = 0.0;    ///< ν

  /// E′ of [XLS21] eq. (88) for an elastic cylinder on a rigid flat [Pa].
  double effective_modulus() const {
    return 2.0 * youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
  }
  /// Half-width b of the contact [m], [XLS21] eq. (88).
  double half_width() const {
    return 2.0 * std::sqrt(2.0 * load * radius / (std::numbers::pi * effective_modulus()));
  }
  /// p_max = 2F / (π b) [Pa], [XLS21] eq. (88).
  double peak_pressure() const { return 2.0 * load / (std::numbers::pi * half_width()); }
  /// p(x) = p_max √(1 − x²/b²) inside the contact, 0 outside [Pa], [XLS21] eq. (89) (as a
  /// compressive magnitude).
  double pressure(double x) const {
    const double r = x / half_width();
    return std::abs(r) < 1.0 ? peak_pressure() * std::sqrt(1.0 - r * r) : 0.0;
  }
  /// The pressure a grid node x_i of spacing h reads from the exact profile [Pa]: its nodal force
  /// ∫ p(x) N_i(x) dx, N_i the linear hat of the node, over h. This, not p(x_i), is what the
  /// measured nodal pressure Σ_p N_i(x_p) f_p / h converges to: the hat averages p over two cells,
  /// which lowers the concave peak and puts pressure on the first node outside the contact
  /// (h = 0.1 mm: 349.4 instead of 353.1 MPa at the centre, 47.4 MPa at x = 0.3 mm > b).
  /// Σ_i h p̄_i = F (partition of unity). Closed form: on each half of the hat, N = a + c x; with
  /// x = b sin θ, p dx = p_max b cos²θ dθ, and ∫ cos²θ = θ/2 + sin 2θ / 4, ∫ sin θ cos²θ = −cos³θ
  /// / 3.
  double nodal_pressure(double node_x, double cell_size) const {
    const double b = half_width(), p_max = peak_pressure();
    const auto piece = [&](double lo, double hi, double a, double c) {
      lo = std::max(lo, -b);
      hi = std::min(hi, b);
      if (!(hi > lo)) return 0.0;
      const auto primitive = [&](double x) {
        const double theta = std::asin(std::clamp(x / b, -1.0, 1.0));
        const double cosine = std::cos(theta);
        return a * (theta / 2.0 + std::sin(2.0 * theta) / 4.0) -
               c * b * cosine * cosine * cosine / 3.0;
      };
      return p_max * b * (primitive(hi) - primitive(lo));
    };
    const double h = cell_size;
    const double force = piece(node_x - h, node_x, 1.0 - node_x / h, 1.0 / h) +
                         piece(node_x, node_x + h, 1.0 + node_x / h, -1.0 / h);
    return force / h;
  }
};

/// The contact pressure at one grid node of the flat.
struct HertzProfilePoint {
  double x = 0.0;               ///< position along the flat, 0 at the centre of contact [m]
  double pressure = 0.0;        ///< simulated [Pa]
  double analytic = 0.0;        ///< [XLS21] eq. (89) [Pa]
  double analytic_nodal = 0.0;  ///< HertzOracle::nodal_pressure, what the node should read [Pa]
};

/// One relaxed level: what it cost, whether it reached equilibrium, and the measured contact.
struct HertzLevel {
  double cell_size = 0.0;  ///< h [m]
  long long particles = 0, steps = 0;
  double dt = 0.0, wall_seconds = 0.0;  ///< largest step [s], run time [s]
  double relaxed_time = 0.0;            ///< simulated time when the convergence test held [s]
  bool converged = false;
  /// Wall reaction [N/m] and its residual |reaction − F| / F when the run stopped.
  double reaction = 0.0, residual = 0.0;
  double kinetic_ratio = 0.0;  ///< kinetic / strain energy when the run stopped
  double half_width = 0.0;     ///< b from the second moment of the contact force [m]
  double peak_pressure = 0.0;  ///< largest nodal pressure [Pa]
  /// RMS error of the nodal pressures against HertzOracle::nodal_pressure over every node where
  /// either is non-zero, over p_max.
  double rms_error = 0.0;
  /// The same against the point values p(x_i) over the nodes inside the contact and any loaded
  /// node outside (reported; it carries the hat's averaging, O(h²/b²) inside and O(h/b) at the
  /// edge).
  double rms_point_error = 0.0;
  std::vector<HertzProfilePoint> profile;  ///< nodes x = i h across the contact and one beyond
};

/// The closed form for the embedded scene `verify/hertz.toml` (E and ν of its material).
HertzOracle hertz_oracle();

/// Relaxes the scene at cell size h with the body-fitted particle layout and measures the contact.
/// Throws std::runtime_error on a numerical failure.
HertzLevel run_hertz_level(double cell_size);

/// Writes DIR/hertz-profile.csv (level, cell_size_m, x_m, pressure_Pa, analytic_Pa,
/// analytic_nodal_Pa) and
/// DIR/hertz-profile.png (the nodal pressures of every level over the analytic ellipse).
void write_hertz_profile(const std::string& directory, const std::vector<HertzLevel>& levels,
                         const HertzOracle& oracle);

}  // namespace fragmpm::pipeline
