#pragma once
// The member folders of a sweep directory and its manifest (README "Many runs"):
//
//   DIR/sweep.toml            the sweep file as it was given
//   DIR/manifest.csv          member, varied values, status, exit code, wall time, steps, balance
//   DIR/NNNN/scene.toml       the member's scene
//   DIR/NNNN/run.h5, run.xmf  its run file
//   DIR/NNNN/fragments/       its fragment tables (fragmpm analyze --csv-only)
//   DIR/NNNN/log.txt          what fragmpm run and fragmpm analyze printed
//   DIR/NNNN/status.txt       written last, by rename: "done" only when run and analysis finished
//
// A member is finished when status.txt says done; anything else (no status, failed, a run
// interrupted before its final frame and status) is run again from the start. A finished member's
// files are never written again.
#include <optional>
#include <string>
#include <vector>

#include "fragmpm/pipeline/sweep_file.hpp"

namespace fragmpm::pipeline {

struct MemberStatus {
  std::string status;  ///< "done", "failed", "interrupted", "pending", "running"
  int exit_code = 0;   ///< of the step that failed (fragmpm run: 2 bad input, 3 numerical)
  double wall_seconds = 0.0;
  long long steps = 0;
  double balance_error = 0.0;  ///< last /series balance_error [J/m]; NaN when unknown
  std::string stage;           ///< "run" or "analyze" for a failure
};

/// The member's status.txt, or nullopt when it has none (never started, or interrupted).
std::optional<MemberStatus> read_member_status(const std::string& member_dir);

/// Finished: status.txt says done and the run file and the fragment series it vouches for exist.
bool member_finished(const std::string& member_dir);

/// Writes status.txt through a temporary file and a rename, so that it is whole or absent.
void write_member_status(const std::string& member_dir, const MemberStatus& status);

/// Writes DIR/manifest.csv from the members' status files (through a rename); a member without one
/// is listed as "pending".
void write_manifest(const SweepSpec& spec, const std::string& dir);

/// One row of a manifest read back: member name, varied values by key, status.
struct ManifestRow {
  std::string member;
  std::vector<std::pair<std::string, std::string>> values;  ///< (key, value) in column order
  MemberStatus status;
};

/// Reads DIR/manifest.csv. Throws std::runtime_error naming the file and line when malformed.
std::vector<ManifestRow> read_manifest(const std::string& dir);

/// Prepares DIR for the sweep: creates it, keeps a copy of the sweep file, and writes each
/// unfinished member's scene.toml. Throws SceneError when a finished member's scene differs from
/// the one the sweep file now gives (another sweep was run into DIR).
void prepare_sweep_dir(const SweepSpec& spec, const std::string& dir);

/// CSV field quoting: fields with a comma, quote or newline are quoted, quotes doubled.
std::string csv_field(const std::string& text);
/// Splits one CSV line (RFC 4180 quoting).
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace fragmpm::pipeline
