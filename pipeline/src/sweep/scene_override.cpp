// Key paths into a parsed scene: "a.b[2].c" walks tables by name and arrays by index.
#include "fragmpm/pipeline/scene_override.hpp"

#include <cctype>
#include <vector>

namespace fragmpm::pipeline {

namespace {

/// One step of a path: a table key, or an array index.
struct Step {
  std::string name;  ///< empty for an index step
  std::size_t index = 0;
  std::string text;  ///< the path up to and including this step, for messages
};

std::vector<Step> parse_path(std::string_view path) {
  std::vector<Step> steps;
  std::string so_far;
  std::size_t i = 0;
  auto bad = [&](const std::string& why) {
    throw KeyPathError("malformed key path '" + std::string(path) + "': " + why);
  };
  if (path.empty()) bad("empty");
  while (i < path.size()) {
    std::size_t j = i;
    while (j < path.size() && path[j] != '.' && path[j] != '[') ++j;
    if (j == i) bad("a name is missing at character " + std::to_string(i + 1));
    const std::string name(path.substr(i, j - i));
    if (!so_far.empty()) so_far += '.';
    so_far += name;
    steps.push_back({name, 0, so_far});
    i = j;
    while (i < path.size() && path[i] == '[') {
      const std::size_t close = path.find(']', i);
      if (close == std::string_view::npos) bad("'[' without ']'");
      const std::string_view digits = path.substr(i + 1, close - i - 1);
      if (digits.empty()) bad("empty index");
      std::size_t index = 0;
      for (char c : digits) {
        if (!std::isdigit(static_cast<unsigned char>(c)))
          bad("index '" + std::string(digits) + "'");
        index = index * 10 + static_cast<std::size_t>(c - '0');
      }
      so_far += '[';
      so_far.append(digits);
      so_far += ']';
      steps.push_back({"", index, so_far});
      i = close + 1;
    }
    if (i < path.size()) {
      if (path[i] != '.') bad("expected '.' or '[' after '" + so_far + "'");
      ++i;
      if (i == path.size()) bad("ends with '.'");
    }
  }
  return steps;
}

std::string what_is(const toml::node* n) {
  if (!n) return "nothing";
  if (n->is_table()) return "a table";
  if (const auto* a = n->as_array())
    return "an array of " + std::to_string(a->size()) + " entr" + (a->size() == 1 ? "y" : "ies");
  return "a value";
}

}  // namespace

const toml::node* find_scene_key(const toml::table& scene, std::string_view path) {
  const toml::node* node = &scene;
  for (const Step& s : parse_path(path)) {
    if (s.name.empty()) {
      const auto* a = node->as_array();
      node = a && s.index < a->size() ? a->get(s.index) : nullptr;
    } else {
      const auto* t = node->as_table();
      node = t ? t->get(s.name) : nullptr;
    }
    if (!node) return nullptr;
  }
  return node;
}

void set_scene_key(toml::table& scene, std::string_view path, const toml::node& value) {
  const std::vector<Step> steps = parse_path(path);
  toml::node* node = &scene;
  std::string parent = "the scene";
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const Step& s = steps[k];
    const bool last = k + 1 == steps.size();
    if (s.name.empty()) {
      auto* a = node->as_array();
      if (!a)
        throw KeyPathError("'" + parent + "' is " + what_is(node) + ", not an array: no '" +
                           s.text + "'");
      if (s.index >= a->size())
        throw KeyPathError("no '" + s.text + "': the scene has " + std::to_string(a->size()) +
                           " entr" + (a->size() == 1 ? "y" : "ies") + " in '" + parent + "'");
      if (last) {
        a->replace(a->begin() + static_cast<std::ptrdiff_t>(s.index), value);
        return;
      }
      node = a->get(s.index);
    } else {
      auto* t = node->as_table();
      if (!t)
        throw KeyPathError("'" + parent + "' is " + what_is(node) + ", not a table: no '" + s.text +
                           "'");
      if (last) {
        t->insert_or_assign(s.name, value);
        return;
      }
      node = t->get(s.name);
      if (!node) throw KeyPathError("no '" + s.text + "' in the scene");
    }
    parent = s.text;
  }
}

}  // namespace fragmpm::pipeline
