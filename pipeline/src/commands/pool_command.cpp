// `fragmpm pool DIR [--replicates N] [--seed S] [--breakage-lower SIZE] [--no-figures]`: pooled
// statistics of a sweep directory (pool.hpp).
#include <cstdio>
#include <memory>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/pipeline/commands.hpp"
#include "fragmpm/pipeline/pool.hpp"
#include "fragmpm/pipeline/units.hpp"

namespace fragmpm::pipeline {

namespace {

struct PoolArguments {
  PoolOptions options;
  std::string lower;
  bool no_figures = false;
};

int execute(PoolArguments a) {
  try {
    if (!a.lower.empty()) a.options.breakage_lower = parse_quantity(a.lower, QuantityKind::length);
    a.options.figures = !a.no_figures;
    if (a.options.replicates < 100) {
      std::fprintf(stderr, "fragmpm pool: --replicates %d: expected at least 100\n",
                   a.options.replicates);
      return 2;
    }
    const std::vector<std::string> files = pool_sweep(a.options, stderr);
    std::fprintf(stderr,
                 "fragmpm pool: wrote %zu files (pool_fits.csv, pool_breakage.csv, "
                 "pool_cdf.csv, pool_grading.csv, pool.h5, pool_figures/)\n",
                 files.size());
    return 0;
  } catch (const PoolError& e) {
    std::fprintf(stderr, "fragmpm pool: %s\n", e.what());
    return 2;
  } catch (const UnitError& e) {
    std::fprintf(stderr, "fragmpm pool: --breakage-lower: %s\n", e.what());
    return 2;
  } catch (const mpm::RunFileError& e) {
    std::fprintf(stderr, "fragmpm pool: %s\n", e.what());
    return 1;
  }
}

}  // namespace

void add_pool_command(CLI::App& app, CommandResult& result) {
  auto a = std::make_shared<PoolArguments>();
  PoolOptions& o = a->options;
  CLI::App* c = app.add_subcommand(
      "pool",
      "Pooled statistics of a sweep directory: CDFs with member-bootstrap bands, grading curves, "
      "Rosin-Rammler and power-law fits, breakage indices; CSV, pool.h5 and figures");
  c->add_option("dir", o.dir, "Sweep directory written by fragmpm sweep")->required();
  c->add_option("--replicates", o.replicates, "Bootstrap resamplings of the members")
      ->capture_default_str();
  c->add_option("--seed", o.seed, "Bootstrap seed (same seed, same bands)")->capture_default_str();
  c->add_option("--points", o.points, "CDF evaluation points")->capture_default_str();
  c->add_option("--min-tail", o.min_tail, "Fewest fragments the power-law d_min may leave above it")
      ->capture_default_str();
  c->add_option("--breakage-lower", a->lower,
                "Hardin's lower size (\"2 um\"; default: one particle's equivalent diameter)");
  c->add_flag("--no-figures", a->no_figures, "Do not write the PNG figures");
  c->callback([a, &result] { result.exit_code = execute(*a); });
}

}  // namespace fragmpm::pipeline
