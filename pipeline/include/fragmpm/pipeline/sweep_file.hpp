#pragma once
// Sweep files: a base scene and what varies across the members of a many-run study (README "Many
// runs"). Reading one builds every member's scene text and compiles it, so that a bad value is
// refused (SceneError: file, line, key; exit 2) before any member runs.
//
//   scene = "base.toml"                       # relative to the sweep file
//   seeds = "1..16"                           # or [1, 5, 9]; sets every Weibull seed of the scene
//   seed_keys = ["materials[0].weibull.seed"] # optional; default: each material with a weibull
//   table [set]                                     # optional: keys set in every member
//   "materials[0].weibull" = { modulus = 6, reference_volume = "1e-15 m3" }
//   [vary]                                    # each key a list; members are the grid of all lists
//   "walls[3].velocity.to" = [["0 m/s", "-10 m/s"], ["0 m/s", "-20 m/s"]]
//   [analyze]                                 # frames analysed in every member (fragmpm analyze)
//   at = ["1 us", "2 us"]   /   at_displacement = ["10 um", "20 um"]
//   min_particles = 4 ; d_mask = 0.99
#include <optional>
#include <string>
#include <vector>

namespace fragmpm::pipeline {

/// One varied key: its path, the sweep-file line of its list, and each value as TOML text.
struct SweepAxis {
  std::string key;  ///< scene key path, or "seed"
  int line = 0;
  std::vector<std::string> values;  ///< display text of each value ("0.1 mm", "[0, -20]")
};

struct SweepMember {
  std::string name;                 ///< folder name below DIR: "0001", "0002", …
  std::vector<std::size_t> choice;  ///< index into each axis's values
  std::string scene_text;           ///< the member's scene, file paths relative to its folder
};

struct SweepAnalysis {
  std::vector<std::string> at;               ///< times or displacements with units
  std::vector<std::string> at_displacement;  ///< platen displacements
  int min_particles = 4;
  double d_mask = 0.99;
};

struct SweepSpec {
  std::string path;        ///< the sweep file
  std::string base_scene;  ///< the base scene file
  /// Varied keys in key order ([vary] is a TOML table; toml++ keeps it sorted), "seed" last.
  std::vector<SweepAxis> axes;
  std::vector<SweepMember> members;  ///< the grid, seeds varying fastest
  SweepAnalysis analysis;
  std::string text;  ///< the sweep file's text
};

/// Reads the sweep file and builds the members whose folders will be `output_dir`/NAME. With
/// `compile`, every member scene is compiled (and the first bad one raises SceneError naming the
/// sweep file, the line of the value that made it bad and its key). Throws SceneError.
SweepSpec read_sweep(const std::string& path, const std::string& output_dir, bool compile);

/// "key = value" of every varied key of a member, comma-separated (for logs).
std::string describe_member(const SweepSpec& spec, const SweepMember& member);

}  // namespace fragmpm::pipeline
