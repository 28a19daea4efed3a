#include <toml++/toml.h>

#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "fragmpm/pipeline/embedded_scenes.hpp"

namespace fragmpm::pipeline {

const std::string& embedded_scene(const std::string& name) {
  const auto& scenes = embedded_scenes();
  const auto found = scenes.find(name);
  if (found == scenes.end()) throw std::out_of_range("no embedded scene '" + name + "'");
  return found->second;
}

std::string toml_number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.17g", value);
  return text;
}

std::string with_overrides(const std::string& text,
                           const std::map<std::string, std::string>& overrides) {
  toml::table table = toml::parse(text);
  for (const auto& [dotted, value] : overrides) {
    const auto dot = dotted.rfind('.');
    toml::table* parent = &table;
    if (dot != std::string::npos) {
      parent = table.at_path(dotted.substr(0, dot)).as_table();
      if (!parent) throw std::invalid_argument("override '" + dotted + "': no such table");
    }
    toml::table parsed = toml::parse("value = " + value);
    parent->insert_or_assign(dotted.substr(dot == std::string::npos ? 0 : dot + 1),
                             std::move(*parsed.get("value")));
  }
  std::ostringstream out;
  out << table;
  return out.str();
}

}  // namespace fragmpm::pipeline
