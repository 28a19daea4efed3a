#pragma once
// One HDF5 file per run (docs/design.md), SI units, plus an XDMF file beside it for ParaView/VisIt.
//   /meta                 attributes: program_version, git_hash, scene_text, scene_path,
//   unit_system,
//                         dimension, modules (one "name: on|off — reason" line each), failure (if
//                         any)
//   /frames/NNNNNN/       attributes time, step; datasets x, v, F, volume0, mass, r1, r2, stress,
//                         damage, surface, body, material (+ temperature when thermal)
//   /series/              time, dt, kinetic, strain, thermal, dissipated, friction_work, wall_work,
//                         gravity_work, balance_error, momentum (steps×D), step,
//                         wall_<name>_force (steps×D), wall_<name>_displacement (steps×D)
//   /checkpoint/          the full state for an exact restart
//   /fragments/           tables of `fragmpm analyze` (run_file_fragments.hpp)
// RunFile writes and continues a run; RunFileReader (run_file_reader.hpp) reads one, read-only.
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"  // RunFileError: unreadable, missing or inconsistent run files
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/series.hpp"
#include "fragmpm/mpm/solver.hpp"

namespace fragmpm::mpm {

struct RunMeta {
  std::string scene_path;
  std::string scene_text;
  std::vector<ModuleDecision> modules;
  std::vector<std::string> wall_names;
};

template <int D>
struct Checkpoint {
  double time = 0.0;
  long long step = 0;
  EnergyAccumulators totals;
  Particles<D> particles;
  PhaseFieldWarmStart<D> phase_field;  ///< empty without a phase-field material
};

/// Names of frame datasets, in the order of docs/design.md
const std::vector<std::string>& all_frame_fields();

template <int D>
class RunFile {
 public:
  /// Creates a new run file (and PATH with .xmf in place of .h5). Refuses to replace an existing
  /// file unless `overwrite` is set.
  static RunFile create(const std::string& path, const RunMeta& meta, bool overwrite);
  /// Opens an existing run file to continue it from its checkpoint.
  static RunFile open_existing(const std::string& path);

  RunFile(RunFile&&) noexcept;
  RunFile& operator=(RunFile&&) noexcept;
  ~RunFile();

  const std::string& path() const;
  RunMeta meta() const;

  /// Writes /frames/NNNNNN (NNNNNN = zero-padded frame index) with the requested fields (empty =
  /// all) and rewrites the XDMF file. Returns the frame index.
  int write_frame(long long step, double time, const Particles<D>& particles,
                  const std::vector<std::string>& fields);
  /// Appends rows to /series (extendible datasets) and flushes the file.
  void append_series(const std::vector<SeriesRow<D>>& rows);
  /// Replaces /checkpoint with this state (bit-exact doubles).
  void write_checkpoint(const Checkpoint<D>& checkpoint);
  std::optional<Checkpoint<D>> read_checkpoint() const;
  /// Drops frames and series rows written after `step` (used when restarting from a checkpoint).
  void truncate_after(long long step);
  /// Records a numerical failure in /meta (attribute `failure`).
  void write_failure(const std::string& diagnostic);
  void flush();

  int frame_count() const;
  /// Reads frame `index` (all datasets present in it). Throws RunFileError if it does not exist.
  Particles<D> read_frame(int index, double* time = nullptr, long long* step = nullptr) const;

 private:
  struct Impl;
  explicit RunFile(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

/// Reads one dataset of /series as a flat vector (row-major for steps×D datasets).
std::vector<double> read_series(const std::string& path, const std::string& name);

/// Writes the frame datasets of `particles` (docs/design.md layout and units attributes; `fields`
/// empty = all, x always) into `group`. Used for run frames and for the /particles group of grain
/// files. Returns the names of the datasets written.
template <int D>
std::vector<std::string> write_particle_datasets(const h5::Group& group,
                                                 const Particles<D>& particles,
                                                 const std::vector<std::string>& fields);
/// Reads the frame datasets of `group`; fields not stored keep the defaults of Particles::resize.
template <int D>
Particles<D> read_particle_datasets(const h5::Group& group);

}  // namespace fragmpm::mpm
