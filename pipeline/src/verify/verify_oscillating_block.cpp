// V7: oscillating-block frictional heating (docs/verification.md; [NBS18] §3, Fig. 6-7). The scene
// scenes/verify/oscillating-block.toml is run at fixed steps Δt = C Δx / v ([NBS18] eq. (45), v the
// bulk wave speed) over CFL factors C, with second-order ([NBS18] eq. (31)-(36)) and first-order
// (eq. (27)) frictional work. Metric: the friction work of the driven interval, W(t_end) − W(t1),
// per unit thickness. There is no closed form ([NBS18] §3); the reference is the second-order value
// at the smallest C run, the stand-in for the limit C → 0. The work done by the driving walls over
// the same interval is reported beside it: the friction work can converge no faster than the
// mechanical response it is taken from.
//
// Three normal stresses N. At the published N = 100 MPa the drive cannot make the interface slide:
// the edges move at most x_max = 0.1 mm, which shears the 25 mm base to about G x_max / 25 mm
// ≈ 4 MPa, far below μ N = 50 MPa. That variant is reported without a target (error column:
// friction work / drive work): its friction work is all spurious, made at the two nodes just
// outside the block's bottom corners, where the block's field holds 1.5-3 % of the node's mass and
// its trial velocity (p + f Δt)/m differs from the base's by tens of m/s; it grows as C falls.
// N = 2 MPa (the scene's value) gives the
// stick–slide–stick interval [NBS18] §3 describes, with the whole interface slipping about 65 µm;
// N = 5 MPa gives partial slip from the edges only, the hardest case for the stick/slip decision.
#include <cmath>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/verify.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr const char* scene_name = "verify/oscillating-block.toml";

struct CycleRun {
  double friction_work = 0.0;  ///< W(t_end) − W(t1) [J/m]
  double drive_work = 0.0;     ///< work of the walls over [t1, t_end] [J/m]
  double cell_size = 0.0;      ///< [m]
  TimedRun timing;
  std::unique_ptr<mpm::Solver<2>> solver;
};

/// The bulk (dilatational) wave speed √((K + 4G/3)/ρ) of [NBS18] eq. (45): 1924 m/s for this
/// material.
double bulk_wave_speed(const mpm::MaterialSpec& m) {
  return std::sqrt((m.bulk_modulus + 4.0 * m.shear_modulus / 3.0) / m.density);
}

const char* order_name(mpm::FrictionWorkOrder order) {
  switch (order) {
    case mpm::FrictionWorkOrder::first:
      return "first-order";
    case mpm::FrictionWorkOrder::second:
      return "second-order";
    case mpm::FrictionWorkOrder::lumped_slip:
      return "lumped-slip";
  }
  return "?";
}

CycleRun run_cycle(double courant, mpm::FrictionWorkOrder order, double normal_stress) {
  mpm::Problem<2> problem =
      parse_scene(embedded_scene(scene_name), std::string("scenes/") + scene_name);
  if (problem.loads.empty() || problem.loads.front().times.empty())
    throw std::runtime_error("oscillating-block: the scene has no normal-load ramp");
  const double load_end = problem.loads.front().times.back();  // t1: the driving starts here
  const double end_time = problem.stop.end_time;
  const double scene_stress = problem.loads.front().tractions.back().norm();
  if (!(scene_stress > 0.0))
    throw std::runtime_error("oscillating-block: the scene's normal load is zero");
  for (auto& traction : problem.loads.front().tractions) traction *= normal_stress / scene_stress;
  CycleRun run;
  run.cell_size = problem.grid.cell_size;
  problem.time.fixed_dt =
      courant * problem.grid.cell_size / bulk_wave_speed(problem.materials.at(0));
  problem.contact.friction_work_order = order;
  problem.output.interval = 0.0;
  run.solver = std::make_unique<mpm::Solver<2>>(std::move(problem));
  char label[96];
  std::snprintf(label, sizeof label, "oscillating-block N = %g MPa %s C = %.4g",
                normal_stress * 1e-6, order_name(order), courant);
  const auto nothing = [](const mpm::Solver<2>&) {};
  const TimedRun loading =
      run_until(*run.solver, load_end, std::string(label) + " (loading)", 0.0, nothing);
  const mpm::EnergyAccumulators at_t1 = run.solver->last_row().totals;
  run.timing = run_until(*run.solver, end_time, label, 0.0, nothing);
  run.timing.wall_seconds += loading.wall_seconds;
  run.timing.steps = run.solver->step_count();
  const mpm::EnergyAccumulators at_end = run.solver->last_row().totals;
  run.friction_work = at_end.friction_work - at_t1.friction_work;
  run.drive_work = at_end.wall_work - at_t1.wall_work;
  return run;
}

}  // namespace

std::vector<VerifyRow> verify_oscillating_block(const VerifyOptions& options) {
  // Halving C from 0.5; [NBS18] Fig. 7 spans the same decade and a half. Partial slip (5 MPa)
  // settles only below C = 1/64, so its full series goes one level further.
  const std::vector<double> quick{0.5, 0.25, 0.125};
  const std::vector<double> full{0.5, 0.25, 0.125, 0.0625, 0.03125, 0.015625};
  std::vector<double> full_partial = full;
  full_partial.push_back(0.0078125);
  struct Variant {
    double normal_stress;  ///< [Pa]
    mpm::FrictionWorkOrder order;
    const std::vector<double>& courants;
  };
  const std::vector<Variant> variants{
      {2e6, mpm::FrictionWorkOrder::second, options.quick ? quick : full},
      {2e6, mpm::FrictionWorkOrder::first, options.quick ? quick : full},
      {2e6, mpm::FrictionWorkOrder::lumped_slip, options.quick ? quick : full},
      {5e6, mpm::FrictionWorkOrder::second, options.quick ? quick : full_partial},
      {5e6, mpm::FrictionWorkOrder::first, options.quick ? quick : full_partial},
      {5e6, mpm::FrictionWorkOrder::lumped_slip, options.quick ? quick : full_partial},
      {100e6, mpm::FrictionWorkOrder::second, options.quick ? quick : full},
      {100e6, mpm::FrictionWorkOrder::lumped_slip, options.quick ? quick : full},
  };
  std::vector<VerifyRow> rows;
  double friction_reference = 0.0, drive_reference = 0.0;
  for (std::size_t v = 0; v < variants.size(); ++v) {
    const Variant& variant = variants[v];
    char name[64];
    std::snprintf(name, sizeof name, "%gMPa-%s", variant.normal_stress * 1e-6,
                  order_name(variant.order));
    std::vector<VerifyRow> friction, drive;
    for (std::size_t k = 0; k < variant.courants.size(); ++k) {
      const CycleRun run = run_cycle(variant.courants[k], variant.order, variant.normal_stress);
      VerifyRow r = level_row("oscillating-block", name, static_cast<int>(k), run.cell_size,
                              *run.solver, run.timing);
      r.metric = "friction_work_J/m";
      r.value = run.friction_work;
      VerifyRow d = r;
      d.metric = "drive_work_J/m";
      d.value = run.drive_work;
      friction.push_back(r);
      drive.push_back(d);
    }
    // Reference: this N's second-order work (and drive work) at its smallest C; the first-order
    // and lumped-slip variants that follow a second-order one share it.
    const bool second = variant.order == mpm::FrictionWorkOrder::second;
    if (second) {
      friction_reference = friction.back().value;
      drive_reference = drive.back().value;
    }
    for (std::size_t k = 0; k < friction.size(); ++k) {
      VerifyRow& f = friction[k];
      VerifyRow& d = drive[k];
      d.reference = drive_reference;
      d.error = relative_error(d.value, d.reference);
      if (variant.normal_stress >= 100e6) {
        f.reference = 0.0;  // stuck: no slip, no friction work; error = work / drive work
        f.error = f.value / d.value;
      } else {
        f.reference = friction_reference;
        f.error = relative_error(f.value, f.reference);
        // V7 in docs/verification.md: second-order heating within 2 % of the limit at C = 0.5
        // (level 0), here for the stick–slide–stick interval (2 MPa); partial slip (5 MPa) is
        // reported beside it.
        if (second && k == 0 && variant.normal_stress == 2e6) {
          f.target_low = 0.98 * f.reference;
          f.target_high = 1.02 * f.reference;
        }
      }
      rows.push_back(f);
      rows.push_back(d);
    }
  }
  return rows;
}

}  // namespace fragmpm::pipeline
