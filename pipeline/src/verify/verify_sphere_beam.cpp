// The sphere-beam impact of [KT19] §5.3 (docs/verification.md, `sphere-beam`): a disk strikes a
// free beam at mid-length, and a phase-field crack crosses the beam's depth. The paper's check is
// the crack energy spent while that crack runs across, against G_c × the area it opens: 217.53 mJ
// against A_f G_c = 212.13 mJ over its 2 mm thickness, 2.5 % apart.
//
// Reading the crack. Cracked means d ≥ 0.9 in a beam particle; cracked particles whose reference
// positions lie within 1.5 particle spacings of each other form one crack. A crack's extent is the
// width of the depth (x, across the beam) its reference positions cover. The crack has crossed
// when the widest one covers 90 % of the depth: the band of d ≥ 0.9 stops a few particle columns
// short of the struck face, where the contact's compression keeps the history low (h = 0.25 mm:
// at most 9.63 of 10 mm). Its propagation runs from the last observation at which the widest crack
// was shorter than a fifth of the depth to the first at which it had crossed ([KT19]'s points (4)
// and (6)), and its energy is the growth of the total crack energy Ψ_f between the two: like the
// paper's, it includes whatever else cracked meanwhile. A second reading that does not depend on
// where the two points fall: the slope of Ψ_f against the widest crack's extent over the
// observations between them (least squares), which is the energy per crack area while it runs.
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <numbers>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "phase_field_snapshots.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr int beam_body = 0;              // scenes/paper/sphere-beam.toml: the beam comes first
constexpr double beam_depth = 10e-3;      // [m] across the beam, along x
constexpr double cracked = 0.9;           // d of a cracked particle
constexpr double started_fraction = 0.2;  // of the depth: a crack shorter than this has not run

struct Crack {
  double extent = 0.0;     ///< width of the depth its reference positions cover [m]
  double mean_y = 0.0;     ///< [m], reference
  double angle_deg = 0.0;  ///< of its principal axis from x, in (−90, 90]
  std::size_t particles = 0;
};

struct BeamState {
  double time = 0.0;
  double fracture_energy = 0.0;  ///< Ψ_f of the whole run [J/m]
  Crack widest;                  ///< the crack with the largest extent
  int cracks = 0;                ///< cracks of at least 4 particles
};

/// Cracks among the beam's cracked particles, by reference position (the reference keeps a crack
/// that has opened into one piece).
BeamState observe(const mpm::Solver<2>& solver, const std::vector<Eigen::Vector2d>& reference,
                  double spacing) {
  const auto& P = solver.particles();
  BeamState s;
  s.time = solver.time();
  s.fracture_energy = solver.accumulators().fracture_energy;
  std::vector<std::size_t> members;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.body[p] == beam_body && P.damage[p] >= cracked) members.push_back(p);
  // Buckets of one reach on the reference lattice; neighbours are in the 3 × 3 buckets around.
  const double reach = 1.5 * spacing;
  auto bucket_of = [&](const Eigen::Vector2d& x) {
    return std::pair{static_cast<std::int64_t>(std::floor(x.x() / reach)),
                     static_cast<std::int64_t>(std::floor(x.y() / reach))};
  };
  auto key = [](std::int64_t i, std::int64_t j) { return (i << 32) ^ (j & 0xffffffff); };
  std::unordered_map<std::int64_t, std::vector<std::size_t>> buckets;
  for (std::size_t k = 0; k < members.size(); ++k) {
    const auto [i, j] = bucket_of(reference[members[k]]);
    buckets[key(i, j)].push_back(k);
  }
  std::vector<int> label(members.size(), -1);
  std::vector<std::size_t> stack;
  int next = 0;
  for (std::size_t seed = 0; seed < members.size(); ++seed) {
    if (label[seed] >= 0) continue;
    label[seed] = next;
    stack.assign(1, seed);
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    Eigen::Vector2d sum = Eigen::Vector2d::Zero();
    Eigen::Matrix2d second = Eigen::Matrix2d::Zero();
    std::size_t n = 0;
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      const Eigen::Vector2d& x = reference[members[k]];
      lo = std::min(lo, x.x());
      hi = std::max(hi, x.x());
      sum += x;
      second += x * x.transpose();
      ++n;
      const auto [i, j] = bucket_of(x);
      for (std::int64_t di = -1; di <= 1; ++di)
        for (std::int64_t dj = -1; dj <= 1; ++dj) {
          const auto found = buckets.find(key(i + di, j + dj));
          if (found == buckets.end()) continue;
          for (std::size_t other : found->second)
            if (label[other] < 0 && (reference[members[other]] - x).norm() <= reach) {
              label[other] = next;
              stack.push_back(other);
            }
        }
    }
    ++next;
    if (n < 4) continue;
    ++s.cracks;
    // The extent counts the particles' own width: a single column spans one spacing.
    const double extent = hi - lo + spacing;
    if (extent <= s.widest.extent) continue;
    const Eigen::Vector2d mean = sum / double(n);
    const Eigen::Matrix2d covariance = second / double(n) - mean * mean.transpose();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> axes(covariance);
    const Eigen::Vector2d major = axes.eigenvectors().col(1);
    double angle = std::atan2(major.y(), major.x()) * 180.0 / std::numbers::pi;
    if (angle <= -90.0) angle += 180.0;
    if (angle > 90.0) angle -= 180.0;
    s.widest = {std::min(extent, beam_depth), mean.y(), angle, n};
  }
  return s;
}

struct BeamVariant {
  const char* name;
  double fracture_energy;  ///< G_c or Ḡ_c [J/m²]
  const char* anisotropy;  ///< TOML of the beam's anisotropy, or nullptr (isotropic)
  double crossing_energy;  ///< G_c of a crack crossing along x (normal along y) [J/m²]
  std::vector<double> figure_times_us;  ///< the paper's phase-field figure of this case
  /// `[contact] partitioning`: "bodies" is the paper's two discrete fields (the scene's);
  /// "auto" adds damage-field partitioning inside the beam, which [KT19] does not have.
  const char* partitioning = "bodies";
};

/// `figure_directory`: where the phase field at the paper's time points goes (empty: nowhere).
std::vector<VerifyRow> run_beam(const BeamVariant& v, double cell_size, int level,
                                const std::string& figure_directory) {
  std::map<std::string, std::string> overrides{{"output.interval", "0.0"}};
  overrides["grid.cell_size"] = toml_number(cell_size);
  overrides["materials[0].fracture_energy"] = toml_number(v.fracture_energy);
  overrides["contact.partitioning"] = std::string("\"") + v.partitioning + "\"";
  std::string text = with_overrides(embedded_scene("paper/sphere-beam.toml"), overrides);
  if (v.anisotropy)
    text =
        insert_after_line(text, "fracture_energy = ", std::string("anisotropy = ") + v.anisotropy);
  mpm::Problem<2> problem = parse_scene(text, "scenes/paper/sphere-beam.toml");
  const double spacing = cell_size / 2.0;  // the scene samples 2 × 2 particles per cell
  const std::vector<Eigen::Vector2d> reference = problem.particles.x;
  mpm::Solver<2> solver(std::move(problem));
  std::vector<BeamState> history;
  PhaseFieldSnapshots snapshots = phase_field_snapshots(v.figure_times_us);
  take_snapshot(snapshots, solver);
  const std::string what = std::string("sphere-beam ") + v.name + " " + cell_label(cell_size);
  const TimedRun run =
      run_until(solver, solver.problem().stop.end_time, what, 1e-6, [&](const mpm::Solver<2>& s) {
        history.push_back(observe(s, reference, spacing));
        take_snapshot(snapshots, s);
        const BeamState& b = history.back();
        std::fprintf(stderr,
                     "    t = %5.1f us: %d crack(s), widest %.2f mm across at y = %.2f mm "
                     "(%.0f deg), crack energy %.2f J/m\n",
                     b.time * 1e6, b.cracks, b.widest.extent * 1e3, b.widest.mean_y * 1e3,
                     b.widest.angle_deg, b.fracture_energy);
      });
  if (!figure_directory.empty()) {
    char stem[64];
    std::snprintf(stem, sizeof stem, "%s-h%gmm-phase-field.png", v.name, cell_size * 1e3);
    write_phase_field_panels(
        snapshots, (std::filesystem::path(figure_directory) / stem).string(),
        std::string("Sphere-beam impact, ") + v.name + ", " + what.substr(what.rfind("h = ")));
  }
  const double through = 0.9 * beam_depth;
  const BeamState* end = nullptr;
  for (const BeamState& b : history)
    if (b.widest.extent >= through) {
      end = &b;
      break;
    }
  const BeamState* start = nullptr;
  for (const BeamState& b : history) {
    if (end && b.time >= end->time) break;
    if (b.widest.extent < started_fraction * beam_depth) start = &b;
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double expected = v.crossing_energy * beam_depth;  // A_f G_c per unit thickness
  auto row = [&](const std::string& metric, double value, double reference) {
    return metric_row(level_row("sphere-beam", v.name, level, cell_size, solver, run), metric,
                      value, reference);
  };
  std::vector<VerifyRow> rows;
  const bool crossed = start && end;
  const double spent = crossed ? end->fracture_energy - start->fracture_energy : nan;
  VerifyRow energy = row("crossing_crack_energy/(G_c depth) (paper 1.025)", spent / expected, 1.0);
  // [KT19] checks the isotropic cases (i) and (ii) against A_f G_c; in (ii) its two cracks merge
  // into one crossing, which is what this reading needs to have a value. The target is for the
  // paper's fields only.
  if (!v.anisotropy && std::string_view(v.partitioning) == "bodies") {
    energy.target_low = 0.95;
    energy.target_high = 1.05;
  }
  rows.push_back(energy);
  rows.push_back(row("crossing_start_us", crossed ? start->time * 1e6 : nan, nan));
  rows.push_back(row("crossing_end_us", crossed ? end->time * 1e6 : nan, nan));
  double slope = nan;
  if (crossed) {
    double n = 0.0, sx = 0.0, sy = 0.0, sxx = 0.0, sxy = 0.0;
    for (const BeamState* b = start; b <= end; ++b) {
      n += 1.0;
      sx += b->widest.extent;
      sy += b->fracture_energy;
      sxx += b->widest.extent * b->widest.extent;
      sxy += b->widest.extent * b->fracture_energy;
    }
    if (n > 2.0 && n * sxx - sx * sx > 0.0) slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  }
  rows.push_back(row("crack_energy_per_crack_area/G_c (slope while crossing)",
                     slope / v.crossing_energy, nan));
  const BeamState& last = history.back();
  rows.push_back(row("widest_crack_extent/depth", last.widest.extent / beam_depth, nan));
  rows.push_back(row("widest_crack_y_mm (impact at 37.5)", last.widest.mean_y * 1e3, nan));
  rows.push_back(row("widest_crack_angle_deg", last.widest.angle_deg, nan));
  rows.push_back(row("cracks_at_end", last.cracks, nan));
  rows.push_back(row("final_crack_energy/(G_c depth)", last.fracture_energy / expected, nan));
  // [KT19] §5.3.1: Ψ_f = 311.82 mJ over the 2 mm thickness once the crack has crossed (case (i)).
  rows.push_back(row("final_crack_energy_J/m (paper case (i): 155.9)", last.fracture_energy,
                     v.anisotropy || v.fracture_energy != 10606.6 ? nan : 311.82e-3 / 2e-3));
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_sphere_beam(const VerifyOptions& options) {
  // Case (i) isotropic G_c = 10.6066 N/mm; case (ii) isotropic 9.75 N/mm; case (iii) orthotropic
  // γ = (80, 1, 0, 74), Ḡ_c = 7.5 N/mm, material axes 45° clockwise from x, whose G_c ranges
  // from 10.6066 to 23.6892 N/mm ([KT19] §5.3). A crack crossing the beam along x has its normal
  // along y; in case (iii) the crack leaves the x axis, so its crossing energy is given as the
  // smallest G_c and the row carries no target.
  const BeamVariant variants[] = {
      {"isotropic", 10606.6, nullptr, 10606.6, {0, 12, 40, 56, 70, 88}},     // Fig. 24
      {"isotropic-9.75", 9750.0, nullptr, 9750.0, {0, 30, 40, 68, 72, 78}},  // Fig. 26
      {"orthotropic-45deg",
       7500.0,
       "{ gamma_1111 = 80, gamma_2222 = 1, gamma_1122 = 0, gamma_1212 = 74, orientation = \"-45 "
       "deg\" }",
       10606.6,
       {0, 12, 28, 40, 70, 80}},  // Fig. 28
      // Case (i) with the crack free to open at separable nodes (d ≥ D_cr = 0.95) as in the
      // Rankine and time-to-failure scenes: reported beside the paper's fields, no target.
      {"isotropic-partitioned", 10606.6, nullptr, 10606.6, {0, 12, 40, 56, 70, 88}, "auto"}};
  // `--quick` runs the three cases and the partitioned case (i) at h = l₀ (minutes each). The full
  // set starts with case (i) at the paper's cell, the run its energy check is about, and prints
  // each run's rows as soon as it ends (each run at the paper's cell takes about an hour on 2
  // cores).
  std::vector<std::string> names;
  for (const BeamVariant& v : variants) names.push_back(v.name);
  check_selection(options, "sphere-beam", names, options.quick ? 1 : 2);
  std::vector<VerifyRow> rows;
  int runs = 0;
  auto add = [&](const BeamVariant& v, double cell_size, int level) {
    if (!selected(options, v.name, level)) return;
    ++runs;
    const std::string figures = case_directory(options, "sphere-beam");
    append_run_rows(options, v.name, cell_size, run_beam(v, cell_size, level, figures), rows);
  };
  if (!options.quick) add(variants[0], 0.125e-3, 1);
  for (const BeamVariant& v : variants) add(v, 0.25e-3, 0);
  if (!options.quick)
    for (const BeamVariant& v : {variants[1], variants[2]}) add(v, 0.125e-3, 1);
  if (runs == 0)
    throw std::invalid_argument(
        "--variant/--level: sphere-beam runs isotropic-partitioned at "
        "level 0 only");
  return rows;
}

}  // namespace fragmpm::pipeline
