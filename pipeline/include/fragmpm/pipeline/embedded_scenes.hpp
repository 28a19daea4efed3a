#pragma once
// Scene files from scenes/ compiled into the program, keyed by their path below scenes/
// (e.g. "verify/bar.toml"), so verification, stability and bench scenes need no install step.
#include <map>
#include <string>

namespace fragmpm::pipeline {

const std::map<std::string, std::string>& embedded_scenes();

/// Text of an embedded scene; throws std::out_of_range naming the scene if it is not there.
const std::string& embedded_scene(const std::string& name);

/// Returns `text` with some keys replaced, e.g. {"grid.cell_size", "\"0.5 mm\""}: each value is a
/// TOML expression. Used to run one scene file at several resolutions.
/// A double as a TOML number that reads back bit for bit (for override values).
std::string toml_number(double value);

std::string with_overrides(const std::string& text,
                           const std::map<std::string, std::string>& overrides);

}  // namespace fragmpm::pipeline
