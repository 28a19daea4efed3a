#pragma once
// Setting one key of a parsed scene by its path, as sweep files name them: "grid.cell_size",
// "walls[1].velocity.to", "materials[0].weibull.seed" (the same dotted path with array indices that
// scene errors report in SceneError::key).
#include <toml++/toml.h>

#include <stdexcept>
#include <string>
#include <string_view>

namespace fragmpm::pipeline {

/// A key path that does not lead into the scene: a table or array entry on the way is missing, an
/// index is out of range, or the path is malformed. what() says which part and what was there.
struct KeyPathError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

/// Replaces (or adds, when only the last name is new) the value at `path` in `scene` by a copy of
/// `value`. Every table and array entry before the last component must exist, so a misspelt section
/// is an error here; a misspelt last key is left to the scene compiler's unknown-key check.
void set_scene_key(toml::table& scene, std::string_view path, const toml::node& value);

/// The node at `path`, or null when some component is missing.
const toml::node* find_scene_key(const toml::table& scene, std::string_view path);

}  // namespace fragmpm::pipeline
