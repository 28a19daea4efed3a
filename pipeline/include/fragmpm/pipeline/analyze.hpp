#pragma once
// `fragmpm analyze` as a function, so that `fragmpm pipeline` and `fragmpm demo` run the same
// analysis (docs/design.md): fragments of chosen frames of a run file, their tables (CSV and
// /fragments/NNNNNN/ in the run file), number- and mass-weighted CDFs of equivalent diameter and
// roundness, fragment count and mean size against time over every frame, and the figures.
#include <cstdint>
#include <cstdio>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "fragmpm/analysis/fragment_tables.hpp"
#include "fragmpm/analysis/fragments.hpp"
#include "fragmpm/analysis/frame_fragments.hpp"

namespace fragmpm::pipeline {

/// Bad input to analyze (missing or foreign file, a frame that does not exist, no damage data, an
/// unknown platen, an unreadable request); the message says what and where. Exit code 2.
struct AnalyzeError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

/// Default damage mask of fragments in a run with the phase field: its AT2 cracks approach d = 1
/// only as the history of an opening crack grows without bound (a bar pulled apart at 1 m/s keeps
/// its crack particles below 0.97 for 15 µs after it has broken), so d ≥ 0.9 marks them, as the
/// plate-impact verification reads its cracks.
inline constexpr double phase_field_fragment_mask = 0.9;

/// particle_fragment of a particle that `--body` left out (another body than the one analysed).
inline constexpr std::int32_t other_body_fragment = -2;

struct AnalyzeOptions {
  std::string run_path;
  /// Times ("20us") or platen displacements ("0.8mm"), told apart by their unit.
  std::vector<std::string> at;
  /// Platen displacements; a bare number is metres.
  std::vector<std::string> at_displacement;
  /// Frame indices, or "first" / "last".
  std::vector<std::string> frames;
  /// Wall whose displacement series measures the platen travel; empty = the only wall that moves.
  std::string platen;
  /// Directory for CSV tables and figures; empty = RUN_fragments beside the run file.
  std::string output_dir;
  analysis::FragmentOptions fragments;
  /// Analyse only the particles of this body (the frames' `body` field: the order of the scene's
  /// bodies and grains); −1 = all. A grain's own fragments, e.g. the top grain of a crushed column.
  int body = -1;
  /// fragments.d_mask was chosen by the user; otherwise a run with a phase-field material is
  /// masked at d ≥ phase_field_fragment_mask (its cracks approach d = 1 only as they open).
  bool d_mask_given = false;
  bool figures = true;         ///< write the PNG figures
  bool write_run_file = true;  ///< write /fragments/ groups into the run file
};

struct AnalyzedFrame {
  int frame = 0;
  long long step = 0;
  double time = 0.0;
  double platen_displacement = 0.0;  ///< NaN when no platen is known
  std::string request;               ///< what selected it ("--at 20us", "default", …)
  analysis::FrameFragments fragments;
};

struct AnalyzeResult {
  std::string output_dir;
  std::string platen;                 ///< the wall used for displacements; empty when none
  std::vector<AnalyzedFrame> frames;  ///< the selected frames, by frame index
  std::vector<analysis::FragmentSeriesPoint> series;  ///< every frame of the run
  std::vector<std::string> files;                     ///< files written
  std::vector<std::string> replaced_groups;           ///< run-file groups replaced
};

/// Runs the analysis and writes its outputs, logging one line per step to `log` (may be null).
/// Throws AnalyzeError for bad input; mpm::RunFileError for HDF5 failures while writing.
AnalyzeResult analyze_run(const AnalyzeOptions& options, std::FILE* log);

}  // namespace fragmpm::pipeline
