// P1: Kalthoff–Winkler ([XLS21] §4.3; [HH17] §3.2). Metrics: the crack angle against the notch
// direction (published 59° ([HH17]), ~67° ([XLS21]), 70° experiment; target 58-72°) and the crack
// speed ([HH17]: 2.0 km/s; target 1.6-2.4 km/s).
//
// The crack is the set of fully damaged plate particles ahead of and above the notch tip. Its
// direction is the principal axis, through the tip, of those particles 3-30 mm from the tip at the
// end; the tip position at each sampled time is the farthest of them along that axis (within 4 mm
// of it). The speed is the least-squares slope of tip distance against time over 40-50 µs, the
// window in which [HH17] §3.2 quotes 2.0 km/s.
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>

#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

const mpm::Vec<2> notch_tip(50e-3, 25e-3);  // [m], scenes/verify/kalthoff.toml
constexpr double fully_damaged = 0.99;

struct Sample {
  double time = 0.0;
  std::vector<mpm::Vec<2>> cracked;  ///< positions of fully damaged particles ahead of the tip
};

std::vector<mpm::Vec<2>> cracked_particles(const mpm::Particles<2>& P) {
  std::vector<mpm::Vec<2>> out;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.body[p] == 0 && P.damage[p] >= fully_damaged && P.x[p][0] > notch_tip[0] - 2e-3 &&
        P.x[p][1] > notch_tip[1])
      out.push_back(P.x[p]);
  return out;
}

/// Unit direction of the crack from the tip (upward component ≥ 0), or zero if none.
mpm::Vec<2> crack_direction(const std::vector<mpm::Vec<2>>& cracked) {
  Eigen::Matrix2d moment = Eigen::Matrix2d::Zero();
  int count = 0;
  for (const auto& x : cracked) {
    const mpm::Vec<2> r = x - notch_tip;
    if (r.norm() < 3e-3 || r.norm() > 30e-3) continue;
    moment += r * r.transpose();
    ++count;
  }
  if (count < 3) return mpm::Vec<2>::Zero();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(moment);
  mpm::Vec<2> axis = eigen.eigenvectors().col(1);
  return axis[1] < 0.0 ? mpm::Vec<2>(-axis) : axis;
}

/// Variants: "default-l_ch" runs the scene as it is (l_ch = 1.13 h, the band width calibrated to
/// dissipate G_f per crack area, mpm::characteristic_length); "paper-l_ch" sets l_ch = cell
/// diagonal as in [HH17] Table II (1.414 mm at h = 1 mm).
std::vector<VerifyRow> run_level(int level, double cell_size, const std::string& variant) {
  std::map<std::string, std::string> overrides{{"grid.cell_size", toml_number(cell_size)},
                                               {"output.interval", "0.0"}};
  if (variant == "paper-l_ch")
    overrides["materials[0].characteristic_length"] = toml_number(cell_size * std::sqrt(2.0));
  const std::string text = with_overrides(embedded_scene("verify/kalthoff.toml"), overrides);
  mpm::Solver<2> solver(parse_scene(text, "scenes/verify/kalthoff.toml"));
  std::vector<Sample> samples;
  const double end_time = solver.problem().stop.end_time;
  const TimedRun timing =
      run_until(solver, end_time, "kalthoff " + variant + " " + cell_label(cell_size), 1e-6,
                [&](const mpm::Solver<2>& s) {
                  samples.push_back({s.time(), cracked_particles(s.particles())});
                });
  const mpm::Vec<2> axis = crack_direction(samples.back().cracked);
  std::vector<VerifyRow> rows;
  VerifyRow angle = level_row("kalthoff", variant, level, cell_size, solver, timing);
  angle.metric = "crack_angle_deg (reference: 70 experiment; target 58-72)";
  angle.reference = 70.0;
  if (axis.squaredNorm() == 0.0) {
    angle.value = 0.0;  // no crack: fails its target
    angle.error = 1.0;
    angle.target_low = 58.0;
    angle.target_high = 72.0;
    rows.push_back(angle);
    return rows;
  }
  angle.value = std::atan2(axis[1], axis[0]) * 180.0 / std::numbers::pi;
  angle.error = relative_error(angle.value, angle.reference);
  angle.target_low = 58.0;  // P1 in docs/verification.md
  angle.target_high = 72.0;
  rows.push_back(angle);
  // Tip distance along the axis over time, then a least-squares speed.
  double st = 0, sl = 0, stt = 0, stl = 0;
  int n = 0;
  for (const auto& sample : samples) {
    double tip = 0.0;
    for (const auto& x : sample.cracked) {
      const mpm::Vec<2> r = x - notch_tip;
      const double along = r.dot(axis);
      if ((r - along * axis).norm() <= 4e-3) tip = std::max(tip, along);
    }
    // [HH17] §3.2 quotes the speed over 40 µs < t < 50 µs (after Belytschko et al.); the crack then
    // slows as it turns towards the top edge, so a fit over the whole path would be another number.
    if (sample.time < 40e-6 * (1.0 - 1e-9) || sample.time > 50e-6 * (1.0 + 1e-9) || tip <= 0.0)
      continue;
    st += sample.time;
    sl += tip;
    stt += sample.time * sample.time;
    stl += sample.time * tip;
    ++n;
  }
  VerifyRow speed = angle;
  speed.metric = "crack_speed_m/s (reference: 2000 from [HH17]; target 1600-2400)";
  speed.reference = 2000.0;
  speed.value = n >= 2 ? (n * stl - st * sl) / (n * stt - st * st) : 0.0;
  speed.error = relative_error(speed.value, speed.reference);
  speed.target_low = 1600.0;
  speed.target_high = 2400.0;
  rows.push_back(speed);
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_kalthoff(const VerifyOptions& options) {
  // 40 000 particles at 1 mm take ~10 minutes; 0.5 mm (8× the work) only without --quick.
  std::vector<VerifyRow> rows;
  for (const std::string variant : {"paper-l_ch", "default-l_ch"}) {
    const std::vector<double> cells = options.quick || variant == "paper-l_ch"
                                          ? std::vector<double>{1e-3}
                                          : std::vector<double>{1e-3, 0.5e-3};
    for (std::size_t level = 0; level < cells.size(); ++level)
      for (auto& r : run_level(static_cast<int>(level), cells[level], variant))
        rows.push_back(std::move(r));
  }
  return rows;
}

}  // namespace fragmpm::pipeline
