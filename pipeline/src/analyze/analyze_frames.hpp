#pragma once
// Reading a run file for `fragmpm analyze`: its frame list, frames with the fields fragments need,
// the platen travel at each frame, and the choice of frames from --at / --at-displacement /
// --frame. Private to analyze.cpp.
#include <cstdint>
#include <string>
#include <vector>

#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"
#include "fragmpm/pipeline/analyze.hpp"

namespace fragmpm::pipeline::analyze_detail {

using FrameInfo = mpm::FrameEntry;

struct RunIndex {
  std::string path;
  std::vector<FrameInfo> frames;  ///< sorted by index
  std::vector<std::string> walls;
};

/// "/frames/000012"
std::string frame_group(int index);

/// Checks that `file` is a 2D run with at least one frame and lists its frames and walls.
RunIndex read_run_index(const mpm::RunFileReader& file);

/// Reads a frame; throws AnalyzeError when it lacks damage or volume0 (fragments need both).
mpm::Particles<2> read_analysis_frame(const mpm::RunFileReader& file, const RunIndex& run,
                                      int index);

/// The /series columns choose_platen and platen_travel use: time, step and every wall's
/// displacement.
std::vector<std::string> platen_series(const RunIndex& run);

/// The wall whose travel measures the platen displacement: `requested` when given (AnalyzeError
/// when the run has no such wall), else the only wall that moves, else "" (none or ambiguous).
/// `moving` lists the walls that move, for messages.
std::string choose_platen(const mpm::RunSeries& series, const RunIndex& run,
                          const std::string& requested, std::vector<std::string>& moving);

/// |u| of `wall` at every frame [m], from /series/wall_<wall>_displacement at the frame's step (or
/// interpolated in time when that step has no row).
std::vector<double> platen_travel(const mpm::RunSeries& series, const RunIndex& run,
                                  const std::string& wall);

struct Selected {
  std::size_t position = 0;  ///< index into run.frames
  std::string request;       ///< how it was chosen, for the log
};

/// The frames to tabulate, in frame order without repeats. `travel` is empty when no platen is
/// known; `moving` names the moving walls for the message when a displacement is asked without one.
std::vector<Selected> select_frames(const AnalyzeOptions& options, const RunIndex& run,
                                    const std::vector<double>& travel,
                                    const std::vector<std::string>& moving);

}  // namespace fragmpm::pipeline::analyze_detail
