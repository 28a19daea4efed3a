// V2: sliding block with four friction laws (docs/verification.md; [NBS18] §3, Fig. 2-5, appendix
// eq. (46)-(54)). The elastic block of scenes/verify/sliding-block.toml is compared at the end of
// the tangential ramp t_f with a rigid block under the same loads: its mean velocity against eq.
// (50)-(51) and the accumulated friction work against eq. (52)-(53) (the rigid-block oracle of
// sliding_block_oracle.hpp).
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"
#include "fragmpm/pipeline/sliding_block_oracle.hpp"
#include "fragmpm/pipeline/verify.hpp"
#include "verify_run.hpp"

namespace fragmpm::pipeline {

namespace {

constexpr double block_length = 0.040;    // l [m], as in the scene
constexpr double block_height = 0.015;    // h [m]
constexpr double slide_distance = 0.085;  // Coulomb slide at t_f [m] ([NBS18] §3)
constexpr double coulomb_coefficient = 0.2;
constexpr double load_ratio = 1.0;      // R
constexpr double ramp_fraction = 0.25;  // t1 = t2 = t_f / 4
constexpr int oracle_steps = 200000;    // RK4 steps for laws without a closed form

/// The rigid-block loading of [NBS18] §3 for the scene's material: v_max = 2 % of √(E/ρ) (31.6
/// m/s).
struct Setup {
  double final_speed = 0.0;  ///< v_max [m/s]
  SlidingBlockLoading loading;
};

Setup setup() {
  const mpm::Problem<2> probe =
      parse_scene(embedded_scene("verify/sliding-block.toml"), "scenes/verify/sliding-block.toml");
  const mpm::MaterialSpec& m = probe.materials.at(0);
  const double E =
      9.0 * m.bulk_modulus * m.shear_modulus / (3.0 * m.bulk_modulus + m.shear_modulus);
  Setup s;
  s.final_speed = 0.02 * std::sqrt(E / m.density);
  s.loading = sliding_block_loading(m.density, block_height, block_length, coulomb_coefficient,
                                    load_ratio, s.final_speed, slide_distance, ramp_fraction);
  return s;
}

struct Variant {
  std::string name;
  std::string friction;  ///< TOML value of contact.friction
  /// Young's modulus of block and base over the scene's, under the scene's loading (the loads
  /// and t_f stay those of the scene's E, so the rigid-block oracle is the same).
  double stiffness_factor = 1.0;
};

/// A block this much stiffer than the scene's stands for the rigid block of the oracle. With the
/// smooth static-dynamic law the scene's elastic block starts to slide early and books 2.7 % more
/// friction work than the oracle; ten times as stiff it books 0.10 % more, while a smaller step at
/// the scene's stiffness does not close the gap (docs/verification.md, sliding-block, with the
/// likely mechanism).
constexpr double stiff_block_factor = 10.0;

/// The four laws of V2 in docs/verification.md (k v_max = 0.5 and S_a = 0.3 N follow the loading)
/// and the smooth static-dynamic law on the stiff block.
std::vector<Variant> variants(const SlidingBlockLoading& b, double final_speed) {
  const std::string smooth_static_dynamic =
      "{ law = \"static-dynamic\", mu_static = 0.4, mu_dynamic = 0.2, half_velocity = 0.05 }";
  return {{"coulomb", toml_number(coulomb_coefficient)},
          {"velocity-dependent", "{ law = \"velocity-dependent\", mu = 0.2, slope = " +
                                     toml_number(0.5 / final_speed) + " }"},
          {"adhesion", "{ law = \"adhesion\", mu = 0.2, shear_strength = " +
                           toml_number(0.3 * b.normal_stress) + " }"},
          {"static-dynamic", smooth_static_dynamic},
          {"static-dynamic-stiff", smooth_static_dynamic, stiff_block_factor}};
}

/// Sets the two traction loads and the end time from the recomputed loading, so that the applied
/// forces are exactly N l (normal, on the top edge) and R N l at t_f (push, on the left edge).
void apply_loading(mpm::Problem<2>& problem, const SlidingBlockLoading& b) {
  bool normal = false, push = false;
  for (mpm::TractionLoad<2>& load : problem.loads) {
    double edge = 0.0;  // loaded boundary length per unit thickness [m]
    for (double a : load.boundary_measure) edge += a;
    if (load.name == "normal") {
      load.times = {0.0, b.normal_ramp_end};
      load.tractions = {mpm::Vec<2>::Zero(), mpm::Vec<2>(0.0, -b.normal_stress * b.length / edge)};
      normal = true;
    } else if (load.name == "push") {
      load.times = {b.tangential_start, b.end_time};
      load.tractions = {mpm::Vec<2>::Zero(),
                        mpm::Vec<2>(b.ratio * b.normal_stress * b.length / edge, 0.0)};
      push = true;
    }
  }
  if (!normal || !push)
    throw SceneError("scenes/verify/sliding-block.toml", 0, "loads",
                     "expected [[loads]] named \"normal\" (top edge) and \"push\" (left edge)");
  problem.stop.end_time = b.end_time;
}

struct Reference {
  double velocity = 0.0;       ///< [m/s]
  double friction_work = 0.0;  ///< [J/m]
};

Reference oracle(const SlidingBlockLoading& b, const mpm::FrictionLaw& law) {
  if (const auto closed = rigid_block_friction(law))
    return {rigid_block_velocity(b, *closed, b.end_time),
            rigid_block_friction_work(b, *closed, b.end_time)};
  // The smooth static/dynamic law ([NBS18] eq. (42)) has no closed-form block motion: integrate it.
  const RigidBlockState s = integrate_rigid_block(b, law, b.end_time, oracle_steps);
  return {s.velocity, s.friction_work};
}

std::vector<VerifyRow> run_level(const SlidingBlockLoading& b, const Variant& variant, int level,
                                 double cell_size, bool computed_normal) {
  const std::string scene = "scenes/verify/sliding-block.toml";
  // With normals from the mass gradients the block's corner nodes get tilted normals, and relative
  // sliding reads as approach there; the position test of [NBS18] eq. (8) is what keeps those nodes
  // apart
  // ([NBS18] §2.4), so that variant turns it on.
  const std::string text = with_overrides(embedded_scene("verify/sliding-block.toml"),
                                          {{"grid.cell_size", toml_number(cell_size)},
                                           {"contact.friction", variant.friction},
                                           {"contact.gap_test", computed_normal ? "true" : "false"},
                                           {"stop.end_time", toml_number(b.end_time)},
                                           {"output.interval", "0.0"}});
  mpm::Problem<2> problem = parse_scene(text, scene);
  for (mpm::MaterialSpec& m : problem.materials) {
    m.bulk_modulus *= variant.stiffness_factor;
    m.shear_modulus *= variant.stiffness_factor;
  }
  apply_loading(problem, b);
  if (computed_normal) problem.contact.normal = mpm::Vec<2>::Zero();  // normals from mass gradients
  const Reference reference = oracle(b, problem.contact.friction);

  int block = -1;
  for (std::size_t i = 0; i < problem.body_names.size(); ++i)
    if (problem.body_names[i] == "block") block = static_cast<int>(i);
  if (block < 0) throw SceneError(scene, 0, "bodies", "expected a body named \"block\"");

  mpm::Solver<2> solver(std::move(problem));
  const TimedRun timing =
      run_until(solver, b.end_time,
                "sliding-block " + variant.name + (computed_normal ? "-computed-normal" : "") +
                    " " + cell_label(cell_size),
                0.0, [](const mpm::Solver<2>&) {});
  const mpm::Particles<2>& P = solver.particles();
  double mass = 0.0, momentum = 0.0;
  for (std::size_t p = 0; p < P.size(); ++p)
    if (P.body[p] == block) {
      mass += P.mass[p];
      momentum += P.mass[p] * P.v[p].x();
    }

  VerifyRow r;
  r.case_name = "sliding-block";
  r.variant = variant.name + (computed_normal ? "-computed-normal" : "");
  r.level = level;
  r.cell_size = cell_size;
  r.particles = static_cast<long long>(P.size());
  r.dt = timing.largest_dt;
  r.steps = timing.steps;
  r.wall_seconds = timing.wall_seconds;
  std::vector<VerifyRow> rows(2, r);
  rows[0].metric = "end_velocity_m/s";
  rows[0].value = momentum / mass;
  rows[0].reference = reference.velocity;
  rows[1].metric = "friction_work_J/m";
  rows[1].value = solver.accumulators().friction_work;
  rows[1].reference = reference.friction_work;
  for (VerifyRow& row : rows) {
    row.error = std::abs(row.value - row.reference) / std::abs(row.reference);
    // Within 2 % for all four laws (the specified normal, as in [NBS18]); the computed normal and
    // the stiff block are reported.
    if (!computed_normal && variant.stiffness_factor == 1.0) {
      row.target_low = row.reference - 0.02 * std::abs(row.reference);
      row.target_high = row.reference + 0.02 * std::abs(row.reference);
    }
  }
  return rows;
}

}  // namespace

std::vector<VerifyRow> verify_sliding_block_level(const std::string& variant_name, int level,
                                                  double cell_size) {
  const Setup s = setup();
  const std::string suffix = "-computed-normal";
  const bool computed_normal = variant_name.ends_with(suffix);
  const std::string law =
      computed_normal ? variant_name.substr(0, variant_name.size() - suffix.size()) : variant_name;
  for (const Variant& v : variants(s.loading, s.final_speed))
    if (v.name == law) return run_level(s.loading, v, level, cell_size, computed_normal);
  throw std::invalid_argument("sliding-block: unknown variant '" + variant_name + "'");
}

std::vector<VerifyRow> verify_sliding_block(const VerifyOptions& options) {
  // 5 mm is the paper's grid; finer levels halve it (the interface stays on a grid line).
  // (13.4 ms of sliding is 13 000 steps at 5 mm, 26 000 at 2.5 mm: the finer level takes minutes.)
  const std::vector<double> cells =
      options.quick ? std::vector<double>{5e-3} : std::vector<double>{5e-3, 2.5e-3};
  std::vector<VerifyRow> rows;
  for (const std::string name : {"coulomb", "velocity-dependent", "adhesion", "static-dynamic",
                                 "static-dynamic-stiff", "coulomb-computed-normal"})
    for (std::size_t l = 0; l < cells.size(); ++l)
      for (VerifyRow& row : verify_sliding_block_level(name, static_cast<int>(l), cells[l]))
        rows.push_back(std::move(row));
  return rows;
}

}  // namespace fragmpm::pipeline
