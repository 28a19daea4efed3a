#pragma once
// Scene files (docs/design.md): TOML with quantities written with units, compiled into an
// mpm::Problem in SI units with particles sampled from the bodies' shapes. The format is described
// in scenes/README.md. Every malformed scene raises SceneError naming file, line, key and what was
// expected; the CLI maps it to exit code 2.
#include <stdexcept>
#include <string>

#include "fragmpm/mpm/problem.hpp"

namespace fragmpm::pipeline {

/// A scene file that cannot be read or is malformed.
/// what() = "FILE:LINE: key 'a.b': expected ..., got ..." (no key part for TOML syntax errors, no
/// line part when the file itself cannot be read, where line = 0).
struct SceneError : std::runtime_error {
  SceneError(std::string file, int line, std::string key, const std::string& detail);
  std::string file;
  int line = 0;  ///< 1-based; 0 = not about a line (unreadable file)
  std::string
      key;  ///< dotted path with array indices, e.g. "bodies[0].radius"; empty for syntax errors
};

/// Reads and compiles the scene file at `path`. Throws SceneError, also for a missing or unreadable
/// file.
mpm::Problem<2> load_scene(const std::string& path);

/// Compiles scene text; `path_for_messages` is used in error messages and stored as
/// Problem::scene_path. Overlapping bodies are not an error (the first body in file order keeps the
/// shared points) but are reported as warnings on stderr.
mpm::Problem<2> parse_scene(const std::string& text, const std::string& path_for_messages);

}  // namespace fragmpm::pipeline
