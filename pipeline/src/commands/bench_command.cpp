// `fragmpm bench`: particle-steps per second next to a memory-bandwidth reference loop timed in the
// same process (docs/design.md), so that the ratio can be compared across machines.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>
#include <numbers>
#include <optional>
#include <string>
#include <vector>

#include "fragmpm/mpm/solver.hpp"
#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/embedded_scenes.hpp"
#include "fragmpm/pipeline/scene.hpp"

namespace fragmpm::pipeline {

namespace {

using Clock = std::chrono::steady_clock;

/// STREAM-style triad a = b + s c over arrays far larger than the caches; best of `repeats`.
/// Returns GB/s counting 24 bytes per element (two loads, one store).
double triad_bandwidth(int threads, std::size_t elements, int repeats) {
  std::vector<double> a(elements), b(elements), c(elements);
#pragma omp parallel for num_threads(threads) schedule(static)
  for (std::int64_t i = 0; i < static_cast<std::int64_t>(elements); ++i) {
    a[i] = 0.0;
    b[i] = 1.0 + 1e-9 * double(i);
    c[i] = 2.0;
  }
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    const auto start = Clock::now();
    const double s = 0.5 + 1e-3 * r;
#pragma omp parallel for num_threads(threads) schedule(static)
    for (std::int64_t i = 0; i < static_cast<std::int64_t>(elements); ++i) a[i] = b[i] + s * c[i];
    best = std::min(best, std::chrono::duration<double>(Clock::now() - start).count());
  }
  volatile double sink = a[elements / 2];
  (void)sink;
  return 24.0 * double(elements) / best / 1e9;
}

struct BenchCase {
  long long target_particles;
  int steps;
};

/// One of the 100 mm blocks of scenes/bench/ (`name`, e.g. "elastic-block", with the scene text
/// `scene`) at about `target_particles`.
mpm::Problem<2> bench_block(const std::string& name, const std::string& scene,
                            long long target_particles) {
  // 2×2 particles per cell over a 100 mm square block: N = 4 (0.1/h)².
  const double cells = std::round(std::sqrt(double(target_particles) / 4.0));
  const double cell_size = 0.1 / cells;
  mpm::Problem<2> problem =
      parse_scene(with_overrides(scene, {{"grid.cell_size", toml_number(cell_size)}}),
                  "scenes/bench/" + name + ".toml");
  for (std::size_t p = 0; p < problem.particles.size(); ++p) {
    const mpm::Vec<2>& x = problem.particles.x[p];
    problem.particles.v[p] = mpm::Vec<2>(0.5 * std::sin(std::numbers::pi * x[1] / 0.1),
                                         0.2 * std::sin(std::numbers::pi * x[0] / 0.1));
  }
  return problem;
}

/// A damage law of the damage-law comparison: its label and the material keys that select it.
struct DamageCase {
  const char* label;
  std::map<std::string, std::string> material;  ///< overrides of materials[0]
  const char* appended = "";                    ///< scene text added at the end (initial cracks)
  mpm::PhaseFieldPreconditioner preconditioner = mpm::PhaseFieldPreconditioner::automatic;
};

/// Three open cracks, 60 mm long, imposed as an initial history (scene text).
constexpr const char* three_open_cracks =
    "\n[[cracks]]\nfrom = [\"20 mm\", \"25 mm\"]\nto = [\"80 mm\", \"25 mm\"]\n"
    "\n[[cracks]]\nfrom = [\"20 mm\", \"50 mm\"]\nto = [\"80 mm\", \"50 mm\"]\n"
    "\n[[cracks]]\nfrom = [\"20 mm\", \"75 mm\"]\nto = [\"80 mm\", \"75 mm\"]\n";

std::vector<DamageCase> damage_cases() {
  const std::map<std::string, std::string> cubic_phase_field = {
      {"damage", "\"phase-field\""},
      {"length_scale", "\"1 mm\""},
      {"fracture_energy", "\"1 J/m2\""},
      {"anisotropy",
       "{ gamma_1111 = 1, gamma_2222 = 1, gamma_1122 = 0, gamma_1212 = 74, orientation = "
       "\"30 deg\" }"}};
  return {
      {"none", {{"damage", "\"none\""}}},
      {"rankine",
       {{"damage", "\"rankine\""}, {"strength", "\"1 MPa\""}, {"fracture_energy", "\"1 J/m2\""}}},
      {"time-to-failure",
       {{"damage", "\"time-to-failure\""},
        {"strength", "\"1 MPa\""},
        {"crack_speed", "\"2 km/s\""}}},
      {"phase-field",
       {{"damage", "\"phase-field\""},
        {"length_scale", "\"1 mm\""},
        {"fracture_energy", "\"1 J/m2\""}}},
      // The same law with three open cracks, 60 mm long, imposed as an initial history (the way
      // the plate's notch is): their particles carry the history of a broken band from the first
      // step, so the crack-block preconditioner is at work in every solve. Cracks that stay put
      // do not make the system as hard as cracks that grow and let pieces fly apart (the
      // colliding rings: README, "Choosing a damage law").
      {"phase-field, cracked",
       {{"damage", "\"phase-field\""},
        {"length_scale", "\"1 mm\""},
        {"fracture_energy", "\"1 J/m2\""}},
       three_open_cracks},
      // The cracked block with the fourth-order term of [KT19] §5.1 (ii)'s cubic anisotropy
      // (γ = (1, 1, 0, 74), axes at 30°), its conjugate gradients preconditioned throughout by
      // the crack block and by multigrid (fragmpm/mpm/aggregation_multigrid.hpp).
      {"pf cubic, block", cubic_phase_field, three_open_cracks,
       mpm::PhaseFieldPreconditioner::crack_block},
      {"pf cubic, multigrid", cubic_phase_field, three_open_cracks,
       mpm::PhaseFieldPreconditioner::multigrid},
  };
}

/// The cost per step of each damage law on scenes/bench/damage-block.toml at 1e5 particles, and of
/// the phase-field stage within its step: the stage's own clock (Solver::phase_field_work) against
/// the rest of the same steps, and against the step without damage.
int run_damage_laws(bool quick, const std::vector<int>& thread_counts,
                    const std::vector<std::string>& only_laws) {
  for (const std::string& wanted : only_laws) {
    const std::vector<DamageCase> cases = damage_cases();
    if (std::none_of(cases.begin(), cases.end(),
                     [&](const DamageCase& c) { return wanted == c.label; })) {
      std::string known;
      for (const DamageCase& c : cases)
        known += std::string(known.empty() ? "" : ", ") + "\"" + c.label + "\"";
      std::fprintf(stderr,
                   "bench: --law \"%s\" is not a row of the damage-law comparison (rows: %s)\n",
                   wanted.c_str(), known.c_str());
      return 2;
    }
  }
  const long long target_particles = 100000;
  const int steps = quick ? 60 : 150;
  std::printf(
      "\ndamage laws (scenes/bench/damage-block.toml: the free block on quadratic B-splines, "
      "%d steps after one warm-up step)\n",
      steps);
  std::printf("%-20s %9s %7s %10s %14s %14s %12s %10s %8s\n", "law", "particles", "threads",
              "ms/step", "phase field ms", "rest of step ms", "pf / rest", "CG iter", "max d");
  for (int threads : thread_counts) {
    double undamaged = 0.0;  // [s] per step without damage
    for (const DamageCase& law : damage_cases()) {
      if (!only_laws.empty() &&
          std::find(only_laws.begin(), only_laws.end(), law.label) == only_laws.end())
        continue;
      omp_set_num_threads(threads);
      std::map<std::string, std::string> overrides;
      for (const auto& [key, value] : law.material) overrides["materials[0]." + key] = value;
      const std::string scene =
          with_overrides(embedded_scene("bench/damage-block.toml"), overrides) + law.appended;
      mpm::Solver<2> solver(bench_block("damage-block", scene, target_particles));
      solver.set_phase_field_preconditioner(law.preconditioner);
      if (auto failure = solver.step()) {
        std::fprintf(stderr, "bench: %s\n", failure->what.c_str());
        return 3;
      }
      const mpm::PhaseFieldWork before = solver.phase_field_work();
      const auto start = Clock::now();
      for (int s = 0; s < steps; ++s)
        if (auto failure = solver.step()) {
          std::fprintf(stderr, "bench: %s\n", failure->what.c_str());
          return 3;
        }
      const double per_step =
          std::chrono::duration<double>(Clock::now() - start).count() / double(steps);
      const mpm::PhaseFieldWork& after = solver.phase_field_work();
      const double phase_field = (after.seconds - before.seconds) / double(steps);
      const double rest = per_step - phase_field;
      double largest_damage = 0.0;
      for (double d : solver.particles().damage) largest_damage = std::max(largest_damage, d);
      if (std::string(law.label) == "none") undamaged = per_step;
      std::printf("%-20s %9zu %7d %10.2f", law.label, solver.particles().size(), threads,
                  1e3 * per_step);
      if (after.runs > 0)
        std::printf(
            " %14.2f %14.2f %12.2f %10.1f", 1e3 * phase_field, 1e3 * rest, phase_field / rest,
            double(after.iterations - before.iterations) / double(after.runs - before.runs));
      else
        std::printf(" %14s %14s %12s %10s", "-", "-", "-", "-");
      std::printf(" %8.3f", largest_damage);
      if (undamaged > 0.0 && std::string(law.label) != "none")
        std::printf("   +%.0f %% over no damage", 100.0 * (per_step / undamaged - 1.0));
      std::printf("\n");
      std::fflush(stdout);
    }
  }
  std::printf(
      "pf / rest: the phase-field stage (assembly, conjugate gradients, interpolation) over the "
      "rest of the same steps.\n");
  return 0;
}

/// A peer scene: a problem other MPM codes run at the same size and step, for side-by-side
/// particle-steps per second. `overrides` pin what the comparison depends on; `quick_stop` shortens
/// the run for --quick.
struct PeerScene {
  std::string label;
  std::string scene;  ///< embedded scene name below scenes/
  std::map<std::string, std::string> overrides;
  std::map<std::string, std::string> quick_stop;
};

std::vector<PeerScene> peer_scenes() {
  return {
      {"block", "bench/block.toml", {{"output.interval", "0.0"}}, {{"stop.max_steps", "30"}}},
      {"disks", "bench/disks.toml", {{"output.interval", "0.0"}}, {{"stop.max_steps", "36"}}},
      // The paper scene itself at its 0.181 mm cell, 0-20 µs (time-to-failure damage, Weibull
      // strengths, three bodies, traction loads; adaptive Δt).
      {"brazilian",
       "paper/brazilian.toml",
       {{"grid.cell_size", "\"0.181 mm\""},
        {"stop.end_time", "\"20 us\""},
        {"output.interval", "0.0"}},
       {{"stop.end_time", "\"2 us\""}}},
  };
}

struct PeerTiming {
  std::size_t particles = 0;
  long long steps = 0;
  double wall = 0.0;  ///< [s]
};

/// Steps a copy of `problem` to its stop condition (end time or step count), timing every step.
std::optional<PeerTiming> time_peer_run(const mpm::Problem<2>& problem) {
  mpm::Solver<2> solver(problem);
  const mpm::StopSpec& stop = problem.stop;
  PeerTiming timing;
  timing.particles = solver.particles().size();
  const auto start = Clock::now();
  while (solver.time() < stop.end_time * (1.0 - 1e-12) && solver.step_count() < stop.max_steps) {
    const double cap = std::isfinite(stop.end_time) ? stop.end_time - solver.time()
                                                    : std::numeric_limits<double>::infinity();
    if (auto failure = solver.step(cap)) {
      std::fprintf(stderr, "bench: %s\n", failure->what.c_str());
      return std::nullopt;
    }
  }
  timing.wall = std::chrono::duration<double>(Clock::now() - start).count();
  timing.steps = solver.step_count();
  return timing;
}

/// Particle-steps per second of the peer scenes, median of `repeats` runs per thread count.
int run_peer_scenes(bool quick, const std::vector<int>& thread_counts, int repeats,
                    std::size_t triad_elements) {
  std::printf(
      "\npeer scenes (the same problems as other MPM codes; whole run timed, median of %d "
      "run(s)%s)\n",
      repeats, quick ? ", shortened by --quick" : "");
  std::printf("%-18s %9s %7s %6s %9s %14s %12s %16s\n", "scene", "particles", "threads", "steps",
              "wall [s]", "particle-steps/s", "triad [GB/s]", "bytes/particle-step");
  for (const PeerScene& peer : peer_scenes()) {
    std::map<std::string, std::string> overrides = peer.overrides;
    if (quick)
      for (const auto& [key, value] : peer.quick_stop) overrides[key] = value;
    const mpm::Problem<2> problem =
        parse_scene(with_overrides(embedded_scene(peer.scene), overrides), "scenes/" + peer.scene);
    for (int threads : thread_counts) {
      omp_set_num_threads(threads);
      std::vector<PeerTiming> runs;
      for (int r = 0; r < repeats; ++r) {
        const auto timing = time_peer_run(problem);
        if (!timing) return 3;
        runs.push_back(*timing);
      }
      std::sort(runs.begin(), runs.end(),
                [](const PeerTiming& a, const PeerTiming& b) { return a.wall < b.wall; });
      const PeerTiming& median = runs[runs.size() / 2];
      const double rate = double(median.particles) * double(median.steps) / median.wall;
      const double bandwidth = triad_bandwidth(threads, triad_elements, quick ? 3 : 5);
      std::printf("%-18s %9zu %7d %6lld %9.3f %14.4g %12.2f %16.1f\n", peer.label.c_str(),
                  median.particles, threads, median.steps, median.wall, rate, bandwidth,
                  bandwidth * 1e9 / rate);
      std::fflush(stdout);
    }
  }
  return 0;
}

int execute(bool quick, std::vector<int> thread_counts, int repeats, bool peers_only,
            bool damage_only, const std::vector<std::string>& only_laws) {
  const std::vector<BenchCase> cases =
      quick ? std::vector<BenchCase>{{10000, 50}, {100000, 8}}
            : std::vector<BenchCase>{{10000, 400}, {100000, 60}, {1000000, 8}};
  if (thread_counts.empty()) {
    thread_counts.push_back(1);
    if (omp_get_num_procs() > 1) thread_counts.push_back(std::min(2, omp_get_num_procs()));
  }
  const std::size_t triad_elements = quick ? (std::size_t(1) << 22) : (std::size_t(1) << 24);
  if (repeats <= 0) repeats = quick ? 1 : 3;
  if (peers_only) return run_peer_scenes(quick, thread_counts, repeats, triad_elements);
  if (damage_only || !only_laws.empty()) return run_damage_laws(quick, thread_counts, only_laws);
  std::printf(
      "fragmpm bench%s: elastic block (one field) and the same block as two touching bodies "
      "(partitioned contact), CPDI, 2x2 particles per cell, %d core(s)\n",
      quick ? " --quick" : "", omp_get_num_procs());
  std::printf("%-18s %9s %7s %6s %9s %14s %12s %16s\n", "scene", "particles", "threads", "steps",
              "wall [s]", "particle-steps/s", "triad [GB/s]", "bytes/particle-step");
  for (const BenchCase& c : cases) {
    for (int threads : thread_counts) {
      double elastic_rate = 0.0;
      for (const std::string scene : {"elastic-block", "partitioned-block"}) {
        omp_set_num_threads(threads);
        mpm::Solver<2> solver(
            bench_block(scene, embedded_scene("bench/" + scene + ".toml"), c.target_particles));
        if (auto failure = solver.step()) {  // warm-up: first touch of the grid and buffers
          std::fprintf(stderr, "bench: %s\n", failure->what.c_str());
          return 3;
        }
        const auto start = Clock::now();
        for (int s = 0; s < c.steps; ++s)
          if (auto failure = solver.step()) {
            std::fprintf(stderr, "bench: %s\n", failure->what.c_str());
            return 3;
          }
        const double wall = std::chrono::duration<double>(Clock::now() - start).count();
        const double rate = double(solver.particles().size()) * c.steps / wall;
        const double bandwidth = triad_bandwidth(threads, triad_elements, quick ? 3 : 5);
        std::printf("%-18s %9zu %7d %6d %9.3f %14.4g %12.2f %16.1f", scene.c_str(),
                    solver.particles().size(), threads, c.steps, wall, rate, bandwidth,
                    bandwidth * 1e9 / rate);
        if (scene == "elastic-block")
          elastic_rate = rate;
        else
          std::printf("   partitioning cost +%.0f %% per particle-step",
                      100.0 * (elastic_rate / rate - 1.0));
        std::printf("\n");
        std::fflush(stdout);
      }
    }
  }
  std::printf(
      "bytes/particle-step = triad bandwidth / particle-step rate: the memory traffic one "
      "particle-step is worth on this machine (lower is better, comparable across machines).\n");
  if (const int code = run_damage_laws(quick, thread_counts, only_laws)) return code;
  return run_peer_scenes(quick, thread_counts, repeats, triad_elements);
}

}  // namespace

void add_bench_command(CLI::App& app, CommandResult& result) {
  auto quick = std::make_shared<bool>(false);
  auto threads = std::make_shared<std::vector<int>>();
  auto repeats = std::make_shared<int>(0);
  auto peers_only = std::make_shared<bool>(false);
  auto damage_only = std::make_shared<bool>(false);
  auto only_laws = std::make_shared<std::vector<std::string>>();
  CLI::App* bench =
      app.add_subcommand("bench", "Particle-steps per second next to a memory-bandwidth reference");
  bench->add_flag("--quick", *quick,
                  "Short run: 1e4 and 1e5 particles only, peer scenes a tenth of their steps");
  bench->add_option("--threads", *threads, "Thread counts to measure (default: 1 and 2)")
      ->delimiter(',');
  bench
      ->add_option(
          "--repeats", *repeats,
          "Runs per peer scene and thread count; the median is shown (default 3, 1 with --quick)")
      ->check(CLI::Range(1, 1000));
  bench->add_flag("--peers-only", *peers_only,
                  "Only the peer scenes (block, disks, Brazilian disk)");
  bench->add_flag("--damage-laws-only", *damage_only,
                  "Only the damage-law comparison (no damage, Rankine, time-to-failure, phase "
                  "field without and with open cracks, at 1e5 particles)");
  bench
      ->add_option("--law", *only_laws,
                   "Only these rows of the damage-law comparison, by label (e.g. \"pf cubic, "
                   "multigrid\"); implies --damage-laws-only")
      ->delimiter(';');
  bench->callback([quick, threads, repeats, peers_only, damage_only, only_laws, &result] {
    result.exit_code = execute(*quick, *threads, *repeats, *peers_only, *damage_only, *only_laws);
  });
}

}  // namespace fragmpm::pipeline
