// `fragmpm bench`: particle-steps per second next to a memory-bandwidth reference loop timed in the
// same process (DESIGN §7), so that the ratio can be compared across machines.
#include <omp.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <numbers>
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


mpm::Problem<2> bench_block(const std::string& scene, long long target_particles) {
  // 2×2 particles per cell over a 100 mm square block: N = 4 (0.1/h)².
  const double cells = std::round(std::sqrt(double(target_particles) / 4.0));
  const double cell_size = 0.1 / cells;
  mpm::Problem<2> problem = parse_scene(
      with_overrides(embedded_scene("bench/" + scene + ".toml"),
                     {{"grid.cell_size", toml_number(cell_size)}}),
      "scenes/bench/" + scene + ".toml");
  for (std::size_t p = 0; p < problem.particles.size(); ++p) {
    const mpm::Vec<2>& x = problem.particles.x[p];
    problem.particles.v[p] = mpm::Vec<2>(0.5 * std::sin(std::numbers::pi * x[1] / 0.1),
                                         0.2 * std::sin(std::numbers::pi * x[0] / 0.1));
  }
  return problem;
}

int execute(bool quick, std::vector<int> thread_counts) {
  const std::vector<BenchCase> cases =
      quick ? std::vector<BenchCase>{{10000, 50}, {100000, 8}}
            : std::vector<BenchCase>{{10000, 400}, {100000, 60}, {1000000, 8}};
  if (thread_counts.empty()) {
    thread_counts.push_back(1);
    if (omp_get_num_procs() > 1) thread_counts.push_back(std::min(2, omp_get_num_procs()));
  }
  const std::size_t triad_elements = quick ? (std::size_t(1) << 22) : (std::size_t(1) << 24);
  std::printf("fragmpm bench%s: elastic block (one field) and the same block as two touching bodies "
              "(partitioned contact), CPDI, 2x2 particles per cell, %d core(s)\n",
              quick ? " --quick" : "", omp_get_num_procs());
  std::printf("%-18s %9s %7s %6s %9s %14s %12s %16s\n", "scene", "particles", "threads", "steps",
              "wall [s]", "particle-steps/s", "triad [GB/s]", "bytes/particle-step");
  for (const BenchCase& c : cases) {
    for (int threads : thread_counts) {
     double elastic_rate = 0.0;
     for (const std::string scene : {"elastic-block", "partitioned-block"}) {
      omp_set_num_threads(threads);
      mpm::Solver<2> solver(bench_block(scene, c.target_particles));
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
      if (scene == "elastic-block") elastic_rate = rate;
      else std::printf("   partitioning cost +%.0f %% per particle-step", 100.0 * (elastic_rate / rate - 1.0));
      std::printf("\n");
      std::fflush(stdout);
     }
    }
  }
  std::printf("bytes/particle-step = triad bandwidth / particle-step rate: the memory traffic one "
              "particle-step is worth on this machine (lower is better, comparable across machines).\n");
  return 0;
}

}  // namespace

void add_bench_command(CLI::App& app, CommandResult& result) {
  auto quick = std::make_shared<bool>(false);
  auto threads = std::make_shared<std::vector<int>>();
  CLI::App* bench = app.add_subcommand("bench", "Particle-steps per second next to a memory-bandwidth reference");
  bench->add_flag("--quick", *quick, "Short run: 1e4 and 1e5 particles only");
  bench->add_option("--threads", *threads, "Thread counts to measure (default: 1 and 2)")->delimiter(',');
  bench->callback([quick, threads, &result] { result.exit_code = execute(*quick, *threads); });
}

}  // namespace fragmpm::pipeline
