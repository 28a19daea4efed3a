// Closed-form checks of the AT2 phase field ([KT19]; docs/verification.md, `phase-field-bar`).
//
// Imposed crack: [KT19] eq. (20) in one dimension with γ = 0 away from a fully cracked line is
// d'' = d / (4 l₀²), so a crack at x = 0 in a strip [−a, a] with free ends has
// d = cosh((a − |x|)/(2 l₀)) / cosh(a/(2 l₀)), and its crack energy G_c ∫ (d²/(4 l₀) + l₀ d'²) dx
// is G_c (tanh(a/(2 l₀)) → 1) per unit crack length. The discrete field is first order in h / l₀.
//
// Pulled bar: a bar whose halves are pulled apart ends with one crack across it, whose energy is
// G_c × the bar's height. The AT2 functional has no elastic range: every stressed particle takes
// some d (phase_field_uniform_damage), so the check needs a bar whose bulk stays well below the
// homogeneous peak stress (9/16) √(E G_c / (6 l₀)) while the crack forms (see the scene).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <stdexcept>

#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify_phase_field.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double length_scale = 1e-3;      // l₀ [m], scenes/verify/phase-field-bar.toml
constexpr double fracture_energy = 100.0;  // G_c [J/m²]
constexpr double bar_height = 2e-3;        // [m]
constexpr double mid_length = 10e-3;       // [m]

struct BarVariant {
  const char* name;
  bool seeded;               ///< partial crack on the mid-length column
  double grip_speed;         ///< [m/s] each way
  const char* partitioning;  ///< [contact] partitioning
  bool target;               ///< the crack energy has the 5 % target
};

/// Crack energy of the bar pulled apart against G_c × height, the share of it the bulk holds, and
/// the energy balance.
std::vector<VerifyRow> run_bar(const BarVariant& v, int level, double cell_size) {
  char speed[64];
  std::snprintf(speed, sizeof speed, "%.17g", v.grip_speed);
  const std::map<std::string, std::string> overrides{
      {"grid.cell_size", toml_number(cell_size)},
      {"output.interval", "0.0"},
      {"walls[0].velocity.to", std::string("[-") + speed + ", 0.0]"},
      {"walls[1].velocity.to", std::string("[") + speed + ", 0.0]"}};
  std::string text = with_overrides(embedded_scene("verify/phase-field-bar.toml"), overrides);
  text += std::string("\n[contact]\npartitioning = \"") + v.partitioning + "\"\n";
  mpm::Problem<2> problem = parse_scene(text, "scenes/verify/phase-field-bar.toml");
  auto& P = problem.particles;
  const double spacing = std::sqrt(P.volume0[0]);
  if (v.seeded) {
    // A partial crack, imposed as [KT19] §5.1 imposes its initial crack, by a history: G_c / s on
    // the particle column at mid-length gives the line d ≈ ½ (the column's H s balances the
    // profile's flux G_c d / (1 − d)) at every resolution.
    for (std::size_t p = 0; p < P.size(); ++p)
      if (std::abs(P.x[p][0] - mid_length) < 0.5 * spacing)
        P.damage_history[p] = fracture_energy / spacing;
  }
  mpm::Solver<2> solver(std::move(problem));
  // The seed's history is energy the mechanics never stored: Σ V₀ g(d) H of the seeded column,
  // which the phase field spends on the crack as d → 1. The balance books that as the history
  // excess (docs/design.md §2.5), which is reported beside it.
  double seed_energy = 0.0;
  for (std::size_t p = 0; p < solver.particles().size(); ++p) {
    const double d = solver.particles().damage[p];
    seed_energy +=
        solver.particles().volume0[p] * (1 - d) * (1 - d) * solver.particles().damage_history[p];
  }
  const double initial = solver.accumulators().fracture_energy;
  const TimedRun run =
      run_until(solver, solver.problem().stop.end_time,
                std::string("phase-field-bar ") + v.name + " " + cell_label(cell_size), 0.0,
                [](const mpm::Solver<2>&) {});
  const auto& Q = solver.particles();
  double bulk = 0.0, largest = 0.0;
  for (std::size_t p = 0; p < Q.size(); ++p) {
    // The crack energy of the particles more than 5 l₀ from mid-length, without the gradient
    // term (their d is nearly uniform): what the AT2 functional spends on the uncracked bar.
    if (std::abs(Q.x[p][0] - mid_length) > 5 * length_scale &&
        std::abs(Q.x[p][0] - mid_length) < 20 * length_scale)
      bulk += Q.volume0[p] * fracture_energy * Q.damage[p] * Q.damage[p] / (4 * length_scale);
    largest = std::max(largest, Q.damage[p]);
  }
  const auto& row = solver.last_row();
  const double input = row.totals.initial_energy + row.totals.wall_work;
  const double reference = fracture_energy * bar_height;
  std::fprintf(stderr,
               "    Psi_f %.5g J/m (initial %.4g), largest d %.6f, balance error %+.4g J/m "
               "(history excess %.4g J/m booked; seed history %.4g J/m)\n",
               row.totals.fracture_energy, initial, largest, row.balance_error,
               row.totals.history_excess, seed_energy);
  std::vector<VerifyRow> rows;
  VerifyRow r = level_row("phase-field-bar", v.name, level, cell_size, solver, run);
  r.metric = "crack_energy/(G_c x height)";
  r.value = row.totals.fracture_energy / reference;
  r.reference = 1.0;
  r.error = relative_error(r.value, 1.0);
  // docs/verification.md: the seeded, partitioned bar within 5 % at every level.
  if (v.target) {
    r.target_low = 0.95;
    r.target_high = 1.05;
  }
  rows.push_back(r);
  r.target_low = -std::numeric_limits<double>::infinity();
  r.target_high = std::numeric_limits<double>::infinity();
  r.metric = "bulk_crack_energy/(G_c x height) (absolute)";
  r.value = r.error = bulk / reference;
  r.reference = 0.0;
  rows.push_back(r);
  r.metric = "balance_error/input (absolute)";
  r.value = r.error = row.balance_error / input;
  rows.push_back(r);
  return rows;
}

/// The two profile-error rows of an imposed crack at one level; returns the row to complete with
/// the crack-energy metric (value, reference 1 and error already set).
VerifyRow push_profile_rows(std::vector<VerifyRow>& rows, const char* variant, std::size_t level,
                            double h, const CrackProfile& c) {
  VerifyRow r;
  r.case_name = "phase-field-bar";
  r.variant = variant;
  r.level = static_cast<int>(level);
  r.cell_size = h;
  r.particles = c.particles;
  r.wall_seconds = c.wall_seconds;
  r.metric = "profile_max_abs_error (absolute)";
  r.value = r.error = c.max_error;
  rows.push_back(r);
  r.metric = "profile_rms_error (absolute)";
  r.value = r.error = c.rms_error;
  rows.push_back(r);
  r.value = c.energy_ratio;
  r.reference = 1.0;
  r.error = relative_error(c.energy_ratio, 1.0);
  return r;
}

constexpr BarVariant bar_variants[] = {{"seeded", true, 0.5, "auto", true},
                                       {"seeded-one-field", true, 0.5, "off", false},
                                       {"unseeded", false, 1.0, "auto", false}};

}  // namespace

// The lattice is grid.min + (i + ½) s, s = h/2, with grid.min.x = −(N + ½) s, so a column sits on
// x = 0; the strip ends half a spacing beyond the outermost columns, a = (n + ½) s.
std::string phase_field_strip_scene(double h, const std::string& shape, int columns_each_side,
                                    double height, const std::string& material_extra) {
  const double s = h / 2.0;
  const double a = (columns_each_side + 0.5) * s;
  const double gmin = -(std::ceil((a + 4 * h) / s) + 0.5) * s;
  char text[2048];
  std::snprintf(text, sizeof text, R"(
[grid]
cell_size = %.17g
min = [%.17g, %.17g]
max = [%.17g, %.17g]
shape_function = "%s"
particles_per_cell = 2
[[materials]]
name = "rock"
E = "10 GPa"
nu = 0.0
density = "2000 kg/m3"
damage = "phase-field"
length_scale = %.17g
fracture_energy = %.17g
%s
[[bodies]]
name = "strip"
material = "rock"
shape = "box"
min = [%.17g, 0.0]
max = [%.17g, %.17g]
[stop]
max_steps = 1
)",
                h, gmin, -4 * h, -gmin, height + 4 * h, shape.c_str(), length_scale,
                fracture_energy, material_extra.c_str(), -a, a, height);
  return text;
}

std::vector<VerifyRow> phase_field_bar_level(const std::string& variant, int level,
                                             double cell_size) {
  for (const BarVariant& v : bar_variants)
    if (variant == v.name) return run_bar(v, level, cell_size);
  throw std::invalid_argument("phase-field-bar: unknown variant '" + variant + "'");
}

CrackProfile phase_field_crack_profile(double cell_size, const std::string& shape,
                                       const std::optional<mpm::PhaseFieldAnisotropy>& anisotropy) {
  const auto start = std::chrono::steady_clock::now();
  const double s = cell_size / 2.0;
  // a ≈ 10 l₀ (20 l₀ for the fourth-order profiles, which decay over up to 4 l₀).
  const int n = static_cast<int>(std::lround((anisotropy ? 20.0 : 10.0) * length_scale / s));
  const double a = (n + 0.5) * s;
  std::string extra;
  double gamma_normal = 0.0;
  if (anisotropy) {
    char text[256];
    std::snprintf(text, sizeof text,
                  "anisotropy = { gamma_1111 = %.17g, gamma_2222 = %.17g, gamma_1122 = %.17g, "
                  "gamma_1212 = %.17g, orientation = %.17g }",
                  anisotropy->gamma_1111, anisotropy->gamma_2222, anisotropy->gamma_1122,
                  anisotropy->gamma_1212, anisotropy->orientation);
    extra = text;
    gamma_normal = mpm::phase_field_normal_gamma(*anisotropy, -anisotropy->orientation);
  }
  // One solve of the strip of this height; its particles and crack energy.
  auto solve = [&](double height) {
    mpm::Problem<2> problem =
        parse_scene(phase_field_strip_scene(cell_size, shape, n, height, extra), "strip.toml");
    auto& P = problem.particles;
    for (std::size_t p = 0; p < P.size(); ++p)
      if (std::abs(P.x[p][0]) < 0.25 * s)
        P.damage_history[p] = 1e8 * fracture_energy / (4.0 * length_scale);
    mpm::Solver<2> solver(std::move(problem));  // the history at step 0 is solved at once
    return std::make_pair(solver.particles(), solver.accumulators().fracture_energy);
  };
  CrackProfile out;
  double energy_per_height = 0.0, height = 1e-3, band = 1.0;
  mpm::Particles<2> Q;
  if (!anisotropy) {
    // Isotropic: the field of a strip 1 mm high is exactly one-dimensional.
    const auto [particles, energy] = solve(height);
    Q = particles;
    energy_per_height = energy / height;
    out.particles = static_cast<long long>(Q.size());
  } else {
    // Rotated material axes couple ∂²d/∂x² with the other second derivatives, so the natural
    // conditions of [KT19] eq. (21) at the strip's free top and bottom bend the field there: the
    // straight crack of the closed form is the middle of a tall strip. The energy per unit crack
    // length is the difference of two heights (10 and 20 l₀; the edges' share cancels), the
    // profile is read within 2 l₀ of the middle of the taller one.
    const auto low = solve(10.0 * length_scale);
    const auto high = solve(20.0 * length_scale);
    energy_per_height = (high.second - low.second) / (10.0 * length_scale);
    Q = high.first;
    height = 20.0 * length_scale;
    band = 2.0 * length_scale;
    out.particles = static_cast<long long>(low.first.size() + high.first.size());
  }
  double sum = 0.0;
  std::size_t counted = 0;
  for (std::size_t p = 0; p < Q.size(); ++p) {
    if (anisotropy && std::abs(Q.x[p][1] - 0.5 * height) > band) continue;
    const double x = std::abs(Q.x[p][0]);
    const double exact =
        anisotropy
            ? mpm::phase_field_straight_crack_profile(gamma_normal, x / length_scale)
            : std::cosh((a - x) / (2.0 * length_scale)) / std::cosh(a / (2.0 * length_scale));
    const double e = Q.damage[p] - exact;
    out.max_error = std::max(out.max_error, std::abs(e));
    sum += e * e;
    ++counted;
  }
  out.rms_error = std::sqrt(sum / double(counted));
  out.energy_ratio =
      energy_per_height / (fracture_energy * mpm::phase_field_straight_crack_energy(gamma_normal));
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

std::vector<VerifyRow> verify_phase_field_bar(const VerifyOptions& options) {
  const std::vector<double> cells = options.quick ? std::vector<double>{0.5e-3, 0.25e-3}
                                                  : std::vector<double>{0.5e-3, 0.25e-3, 0.125e-3};
  std::vector<VerifyRow> rows;
  for (std::size_t level = 0; level < 3; ++level) {
    const double h = 0.5e-3 / double(1 << level);
    VerifyRow r = push_profile_rows(rows, "imposed-crack", level, h,
                                    phase_field_crack_profile(h, "bspline2"));
    r.metric = "crack_energy/(G_c x height)";
    r.target_low = 0.95;
    r.target_high = 1.05;
    rows.push_back(r);
  }
  // The fourth-order anisotropic density ([KT19] §2.2) with the paper's cubic γ = (1, 1, 0, 74):
  // the crack normal along ξ₁ (φ = 0, γ_n = 1, energy √2 Ḡ_c, profile (1 + u) e^(−u)) and at 45°
  // from it (γ_n = 19, energy 2.315 Ḡ_c): the paper's G_c,min and G_c,max of §5.1 case (ii).
  for (const double degrees : {0.0, 45.0})
    for (std::size_t level = 0; level < 3; ++level) {
      const double h = 0.5e-3 / double(1 << level);
      mpm::PhaseFieldAnisotropy cubic{1.0, 1.0, 0.0, 74.0, degrees * std::acos(-1.0) / 180.0};
      VerifyRow r = push_profile_rows(rows, degrees == 0.0 ? "cubic-0deg" : "cubic-45deg", level, h,
                                      phase_field_crack_profile(h, "bspline2", cubic));
      r.metric = "crack_energy/(G_c x height x closed form)";
      rows.push_back(r);
    }
  for (const BarVariant& v : bar_variants)
    for (std::size_t level = 0; level < cells.size(); ++level)
      for (auto& r : run_bar(v, static_cast<int>(level), cells[level])) rows.push_back(r);
  return rows;
}

}  // namespace fragmpm::pipeline
