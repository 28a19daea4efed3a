#pragma once
// `fragmpm pool DIR`: pooled statistics over a sweep's finished members (README "Many runs",
// docs/design.md "Pooled statistics"). Members with identical varied values (seeds pooled) form a
// group; the k-th analysed frame of every member of a group is pooled (k = 0 is the first frame,
// the initial grains).
#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace fragmpm::pipeline {

struct PoolError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// One analysed frame of one member, read from its fragment tables.
struct PoolFrame {
  int frame = 0;
  double time = 0.0;                       ///< [s]
  double platen_displacement = 0.0;        ///< [m], NaN without a platen
  double wall_work = 0.0;                  ///< /series wall_work at the frame [J/m]
  std::vector<double> d, roundness, mass;  ///< resolved fragments
  std::vector<double> all_d, all_mass;     ///< fragments and fines (the grading curve)
  double particle_size = 0.0;  ///< equivalent diameter of one particle (median area / particles)
};

struct PoolMember {
  std::string name;
  std::vector<PoolFrame> frames;  ///< in frame order
};

struct PoolGroup {
  std::string label;                                        ///< "key = value, …" or "all members"
  std::vector<std::pair<std::string, std::string>> values;  ///< varied values except the seed
  std::vector<PoolMember> members;
};

/// Reads DIR/manifest.csv and every finished member's fragment tables and /series wall_work.
/// Throws PoolError naming the file when something is missing or malformed.
std::vector<PoolGroup> read_pool_groups(const std::string& dir, std::FILE* log);

struct PoolOptions {
  std::string dir;
  int replicates = 1000;        ///< bootstrap resamplings of the members
  std::uint64_t seed = 1;       ///< bootstrap seed
  int points = 80;              ///< CDF evaluation points
  std::size_t min_tail = 25;    ///< smallest tail the power-law d_min may leave
  double breakage_lower = 0.0;  ///< Hardin's lower size [m]; 0 = one particle's diameter
  bool figures = true;
};

/// Computes and writes DIR/pool_*.csv, DIR/pool.h5 and DIR/pool_figures/*.png; returns the files.
std::vector<std::string> pool_sweep(const PoolOptions& options, std::FILE* log);

}  // namespace fragmpm::pipeline
