#pragma once
#include <cmath>
#include <limits>
// `fragmpm verify`: verification cases at successive resolutions against closed-form or published
// answers (docs/design.md), and the stability scenes (`--stability`).
#include <functional>
#include <string>
#include <vector>

namespace fragmpm::pipeline {

/// One row of DIR/CASE.csv: `case, variant, level, cell_size_m, particles, dt_s, steps, wall_s,
/// metric, value, reference, error`. `error` is |value − reference| / |reference|, or an absolute
/// error in the metric's unit when the reference is zero (the metric name says so).
struct VerifyRow {
  std::string case_name;
  std::string variant;
  int level = 0;
  double cell_size = 0.0;  ///< [m]
  long long particles = 0;
  double dt = 0.0;  ///< largest (typical) step used [s]
  long long steps = 0;
  double wall_seconds = 0.0;
  std::string metric;
  double value = 0.0;
  double reference = 0.0;
  double error = 0.0;
  /// Acceptance band of `value` from docs/verification.md ("done when"); a row without a
  /// target has the whole line. report_case says PASS or FAIL for rows with a target.
  double target_low = -std::numeric_limits<double>::infinity();
  double target_high = std::numeric_limits<double>::infinity();
  bool has_target() const { return std::isfinite(target_low) || std::isfinite(target_high); }
  bool passed() const { return value >= target_low && value <= target_high; }
};

struct VerifyOptions {
  bool quick = false;  ///< fewer, coarser levels (CI)
  int threads = 0;
  /// Where cases that write more than CASE.csv (the Hertz pressure profile, the Brazilian CDFs)
  /// put their files.
  std::string output_directory = "verify-out";
  /// `--variant`: only these variants of a case that offers the choice (variant_selection_cases);
  /// empty: every variant.
  std::vector<std::string> variants;
  /// `--level`: only this level of the case (0 the coarsest); −1: every level the run runs.
  int level = -1;
  /// `--max-steps`: the runs kept in a run file (stored_run.hpp: plate-impact at the paper's cell)
  /// stop after this many steps of this invocation, to be continued by the same command; 0: run
  /// to the end.
  long long max_steps = 0;
};

/// The cases whose runs `--variant` and `--level` can pick among: the long phase-field runs at
/// the papers' resolutions, which take up to hours each.
const std::vector<std::string>& variant_selection_cases();

/// Whether the run of `variant` at `level` belongs to the selection of `options`.
bool selected(const VerifyOptions& options, const std::string& variant, int level);

/// Throws std::invalid_argument, naming what the case has, when `options` names a variant that
/// is not among `variants` or a level outside [0, levels).
void check_selection(const VerifyOptions& options, const std::string& case_name,
                     const std::vector<std::string>& variants, int levels);

struct VerifyCase {
  std::string name;
  std::string description;
  std::function<std::vector<VerifyRow>(const VerifyOptions&)> run;
};

/// Every verification case, in the order `fragmpm verify` runs them without arguments.
const std::vector<VerifyCase>& verify_cases();

/// V1: axial vibration of an elastic bar (docs/verification.md), CPDI and linear shape functions.
std::vector<VerifyRow> verify_bar(const VerifyOptions& options);

/// V2: sliding block with four friction laws against the rigid-block oracle (docs/verification.md;
/// [NBS18] §3): end-of-slide velocity and friction work per variant (law) and cell size.
std::vector<VerifyRow> verify_sliding_block(const VerifyOptions& options);

/// One level of V2: `variant` is a law ("coulomb", "velocity-dependent", "adhesion",
/// "static-dynamic"), optionally suffixed "-computed-normal" (normals from mass gradients instead
/// of the specified (0, 1)); returns the velocity and friction-work rows.
std::vector<VerifyRow> verify_sliding_block_level(const std::string& variant, int level,
                                                  double cell_size);

/// P2: self-contact against two-body contact and a single field ([HH17] §3.1).
std::vector<VerifyRow> verify_billet(const VerifyOptions& options);

/// V6: dissipated energy of a notched bar against G_f × formed crack ([HH17] §3.3).
std::vector<VerifyRow> verify_notched_bar(const VerifyOptions& options);

/// Fracture energy of a bar pulled apart (one weaker particle column): damage dissipation against
/// G_f × height at three resolutions, and the width of the fully damaged band against l_ch.
std::vector<VerifyRow> verify_bar_tension(const VerifyOptions& options);

/// The AT2 phase field ([KT19]): the profile of an imposed crack against its closed form at three
/// resolutions, and the crack energy of a bar pulled apart against G_c × height
/// (verify_phase_field.hpp, docs/verification.md).
std::vector<VerifyRow> verify_phase_field_bar(const VerifyOptions& options);
/// [KT19] §5.1 plate under impact loading, quick variant (h = 0.25 mm): crack start, speed against
/// the Rayleigh speed, branching, crack energy; isotropic and cubic (`quick`: isotropic only).
std::vector<VerifyRow> verify_plate_impact(const VerifyOptions& options);
/// [KT19] §5.3 sphere-beam impact, phase-field beam: the crack energy spent while the median crack
/// crosses the beam against G_c × depth, crack extent, position and angle; isotropic at h = 0.25 mm
/// (`quick`), and the three surface energies of the paper at its h = 0.125 mm.
std::vector<VerifyRow> verify_sphere_beam(const VerifyOptions& options);
/// [KT19] §5.2 two rings colliding at ±10 and ±20 m/s: pieces per ring against the paper's 2 and 5,
/// crack energy; h = 1 mm (`quick`) and the paper's 0.5 mm.
std::vector<VerifyRow> verify_two_rings(const VerifyOptions& options);
/// P1: Kalthoff–Winkler crack angle and speed ([XLS21] §4.3; [HH17] §3.2).
std::vector<VerifyRow> verify_kalthoff(const VerifyOptions& options);
/// P5: Brazilian disk fragment statistics at two resolutions, three Weibull seeds, partitioned and
/// single-field ([HH17] §3.4); writes the pooled CDF figures.
std::vector<VerifyRow> verify_brazilian(const VerifyOptions& options);

/// V4: one-dimensional conduction from a temperature step against the erfc solution.
std::vector<VerifyRow> verify_conduction(const VerifyOptions& options);

/// V3: steady contact-face temperatures across a pressed interface with pressure-dependent
/// conductance, κ̄ = 0.1, 1, 10 ([XLS21] §4.2, eq. (90)); metrics in K (absolute errors).
std::vector<VerifyRow> verify_contact_temperature(const VerifyOptions& options);

/// V5: Hertz line contact of an elastic cylinder on a rigid flat ([XLS21] §4.1, eq. (88)-(89)):
/// contact half-width and RMS pressure error at h = 0.2, 0.1, 0.05 mm (`quick`: the first two),
/// relaxed to equilibrium; also writes DIR/hertz-profile.csv and .png (verify_hertz.hpp).
std::vector<VerifyRow> verify_hertz(const VerifyOptions& options);

/// V7: oscillating-block frictional heating over CFL factors, first- and second-order heating
/// ([NBS18] §3, Fig. 6-7): friction work of one stick–slide–stick interval against its C → 0 limit.
std::vector<VerifyRow> verify_oscillating_block(const VerifyOptions& options);
/// P3: disk squish ([XLS21] §4.4; [HH17] Fig. 9) isothermal, coupled and with thermal-softening
/// friction: peak contact temperature [K], disk speed [m/s] and friction work per variant.
std::vector<VerifyRow> verify_disk_squish(const VerifyOptions& options);

/// Observed order of convergence log(e_a/e_b)/log(h_a/h_b) between consecutive levels of one
/// variant and metric, in Δt instead of h when both levels share the cell size; NaN where
/// undefined.
double observed_order(const VerifyRow& coarse, const VerifyRow& fine);

/// Writes DIR/CASE.csv (DIR/CASE-SELECTION.csv when `selection` is not empty, so that a run of
/// one variant keeps the full table of an earlier run; creating DIR) and prints the table with
/// orders and PASS/FAIL against each row's target to stdout. Returns false when a row with a target
/// missed it. No rows (every run of the selection stopped short by --max-steps) writes nothing,
/// says so and returns true.
bool report_case(const std::string& directory, const std::string& case_name,
                 const std::vector<VerifyRow>& rows, const std::string& selection = "");

struct StabilityResult {
  std::string scene;
  bool passed = false;
  std::vector<std::string> checks;  ///< "invariant: value vs limit — ok|FAIL"
  double wall_seconds = 0.0;
};

/// Runs every stability scene; each checks its invariants and never crashes or hangs.
std::vector<StabilityResult> run_stability(const VerifyOptions& options);

/// One stability scene (scenes/stability/NAME.toml) with its checks; std::invalid_argument for an
/// unknown name.
StabilityResult run_stability_scene(const std::string& name);
/// The stability scenes' names, in run order.
std::vector<std::string> stability_scene_names();

}  // namespace fragmpm::pipeline
