#pragma once
// `fragmpm pipeline` as a function, shared with `fragmpm demo` (docs/design.md):
// micrograph → segmentation preview → scene with the image's grains → run file + XDMF → fragment
// tables and CDF figures (analyze_run) → field figures of the last frame, energy and
// force–displacement plots → summary.txt, all in one output directory.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

namespace fragmpm::pipeline {

/// Bad input to the pipeline (unreadable image, a scene without an image body, an output directory
/// that is not empty); the message says what and where. Exit code 2.
struct PipelineError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct PipelineOptions {
  std::string image;  ///< the micrograph; replaces `image` of every [[bodies]] entry that has one
  std::string scene_text;  ///< the scene file's text
  std::string
      scene_path;  ///< where the scene came from (messages; relative paths other than image)
  std::string output_dir;
  bool overwrite = false;  ///< allow a non-empty output_dir (files of the same name are replaced)
  int threads = 0;         ///< OpenMP threads; 0 = the default
  bool progress = true;    ///< progress line with ETA while running (on a terminal only)
};

struct PipelineResult {
  int exit_code = 0;               ///< 0, or 3 after a numerical failure (frames so far kept)
  std::string run_path;            ///< DIR/run.h5 (XDMF beside it: DIR/run.xmf)
  std::string summary_path;        ///< DIR/summary.txt
  std::string summary;             ///< its text
  std::vector<std::string> files;  ///< everything written, in order
};

/// Runs the whole pipeline, logging progress to `log` (may be null). Throws PipelineError for bad
/// input — also for scene errors (SceneError's message) and image errors — before anything is
/// simulated, and for an output directory that exists and is not empty unless `overwrite`.
PipelineResult run_pipeline(const PipelineOptions& options, std::FILE* log);

/// The scene text with `image` of every [[bodies]] entry that has one replaced by `image_path`,
/// edited in place so that line numbers in later messages still match the file. Throws
/// PipelineError for a TOML syntax error or when no entry has an `image` key.
std::string scene_with_image(const std::string& scene_text, const std::string& scene_path,
                             const std::string& image_path);

}  // namespace fragmpm::pipeline
