#pragma once
// Read-only access to a run file (layout in run_file.hpp): /meta, the frame list, frames and
// /series, for the commands that only look at a finished or running run (analyze, render, pipeline
// figures). RunFile<D> is the writer; both share the layout code, so a run file is read one way
// everywhere.
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/run_file.hpp"  // RunMeta

namespace fragmpm::mpm {

/// The file is HDF5 but not a FragMPM run file (no /meta, /frames or /series group, or no
/// dimension in /meta). The message is "PATH: not a FragMPM run file (why)".
struct NotARunFile : RunFileError {
  using RunFileError::RunFileError;
};

/// One frame of the run file: /frames/NNNNNN with its attributes and the datasets it holds.
struct FrameEntry {
  int index = 0;  ///< NNNNNN
  long long step = 0;
  double time = 0.0;                ///< [s]
  std::size_t points = 0;           ///< rows of x
  std::vector<std::string> fields;  ///< datasets present, in the order of all_frame_fields()
  bool has(const std::string& field) const;
};

/// /series in memory: every dataset read (or those asked for) as doubles, row-major (momentum and
/// the wall datasets are steps × D).
struct RunSeries {
  std::string source;  ///< the run file's path, for messages
  int dimension = 2;
  std::map<std::string, std::vector<double>> columns;

  bool has(const std::string& name) const { return columns.count(name) != 0; }
  /// Throws RunFileError "SOURCE: /series/NAME: no such series" when the file had no such dataset.
  const std::vector<double>& column(const std::string& name) const;
  static std::string wall_force(const std::string& wall) { return "wall_" + wall + "_force"; }
  static std::string wall_displacement(const std::string& wall) {
    return "wall_" + wall + "_displacement";
  }
};

/// An open run file, read-only. Move-only.
class RunFileReader {
 public:
  /// Opens PATH read-only. Throws RunFileError when HDF5 cannot open it, NotARunFile when it lacks
  /// the run-file groups or /meta's dimension.
  static RunFileReader open(const std::string& path);

  const std::string& path() const { return path_; }
  int dimension() const { return dimension_; }
  /// /meta as written by RunFile::create (throws RunFileError when an attribute is missing).
  RunMeta meta() const;
  /// /meta wall_names; empty when the attribute is absent.
  const std::vector<std::string>& wall_names() const { return walls_; }

  /// The frames, sorted by index.
  const std::vector<FrameEntry>& frames() const { return frames_; }
  /// Frame `index` (NNNNNN), or nullptr.
  const FrameEntry* find_frame(int index) const;
  /// Reads frame `index`; fields not stored keep the defaults of Particles::resize. Throws
  /// RunFileError when the frame does not exist or the run is not D-dimensional.
  template <int D>
  Particles<D> read_frame(int index, double* time = nullptr, long long* step = nullptr) const;

  /// Reads /series: the datasets named in `only` that exist, or all of them when `only` is empty.
  RunSeries read_series(const std::vector<std::string>& only = {}) const;

  /// What lies at /fragments/NAME (NAME = "NNNNNN" or "series"): see FragmentGroupWriter.
  struct GroupState {
    bool exists = false;
    bool is_group = false;
    std::string written_by;  ///< its `written_by` attribute, "" when absent
  };
  GroupState fragment_group(const std::string& name) const;

 private:
  RunFileReader(h5::File file, std::string path);
  h5::File file_;
  std::string path_;
  int dimension_ = 0;
  std::vector<std::string> walls_;
  std::vector<FrameEntry> frames_;
};

}  // namespace fragmpm::mpm
