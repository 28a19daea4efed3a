// Typed reading of TOML scene tables; every failure becomes a SceneError with file, line and key.
#include "scene_toml.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "fragmpm/pipeline/scene.hpp"

namespace fragmpm::pipeline {

namespace {
std::string format_scene_error(const std::string& file, int line, const std::string& key,
                               const std::string& detail) {
  std::string out = file;
  if (line > 0) {
    out += ':';
    out += std::to_string(line);
  }
  out += ": ";
  if (!key.empty()) {
    out += "key '";
    out += key;
    out += "': ";
  }
  out += detail;
  return out;
}
}  // namespace

SceneError::SceneError(std::string file_, int line_, std::string key_, const std::string& detail)
    : std::runtime_error(format_scene_error(file_, line_, key_, detail)),
      file(std::move(file_)),
      line(line_),
      key(std::move(key_)) {}

namespace scene_detail {
namespace {

int node_line(const toml::node& n) {
  return static_cast<int>(n.source().begin.line);
}

std::string quantity_expectation(QuantityKind kind) {
  const std::string_view n = kind_name(kind);
  const bool vowel = n.find_first_of("aeiou") == 0;
  return std::string(vowel ? "an " : "a ") + std::string(n) + " (a number in " +
         std::string(si_unit(kind)) + " or a string with a unit)";
}

/// Edit distance, for "did you mean" hints on misspelt keys.
std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

void fail(const std::string& file, int line, const std::string& key, const std::string& detail) {
  throw SceneError(file, line, key, detail);
}

std::string describe(const toml::node& node) {
  std::ostringstream os;
  if (const auto* s = node.as_string()) return "\"" + s->get() + "\"";
  if (const auto* i = node.as_integer()) return std::to_string(i->get());
  if (const auto* f = node.as_floating_point()) {
    os << f->get();
    return os.str();
  }
  if (const auto* b = node.as_boolean()) return b->get() ? "true" : "false";
  if (const auto* a = node.as_array()) {
    os << *a;
    const std::string text = os.str();
    if (text.size() <= 60 && text.find('\n') == std::string::npos) return text;
    return "an array of " + std::to_string(a->size()) + " elements";
  }
  if (node.is_table()) return "a table";
  return "a date/time value";
}

std::string si(double value, std::string_view unit) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.6g", value);
  return std::string(buf) + " " + std::string(unit);
}

Section::Section(const toml::table& table, std::string path, const std::string& file)
    : table_(&table), path_(std::move(path)), file_(&file) {}

int Section::line() const {
  return node_line(*table_);
}

std::string Section::key(std::string_view k) const {
  return path_.empty() ? std::string(k) : path_ + "." + std::string(k);
}

const toml::node* Section::find(std::string_view k) const {
  return table_->get(k);
}

int Section::line_of(std::string_view k) const {
  const toml::node* n = find(k);
  return n ? node_line(*n) : line();
}

void Section::fail(std::string_view k, const std::string& detail) const {
  scene_detail::fail(*file_, line_of(k), key(k), detail);
}

void Section::fail_table(const std::string& detail) const {
  scene_detail::fail(*file_, line(), path_, detail);
}

void Section::expected(std::string_view k, const std::string& what) const {
  const toml::node* n = find(k);
  fail(k, "expected " + what + ", got " + (n ? describe(*n) : std::string("nothing")));
}

void Section::allow_only(std::initializer_list<std::string_view> allowed) const {
  allow_only(std::vector<std::string_view>(allowed));
}

void Section::allow_only(const std::vector<std::string_view>& allowed) const {
  for (auto&& [k, v] : *table_) {
    const std::string_view name = k.str();
    if (std::find(allowed.begin(), allowed.end(), name) != allowed.end()) continue;
    std::string list, hint;
    for (std::string_view a : allowed) {
      list += (list.empty() ? "" : ", ") + std::string(a);
      if (hint.empty() && edit_distance(name, a) <= 2)
        hint = " (did you mean '" + std::string(a) + "'?)";
    }
    scene_detail::fail(*file_, static_cast<int>(k.source().begin.line), key(name),
                       "unknown key" + hint + ": expected one of " + list);
  }
}

const toml::node& Section::require(std::string_view k) const {
  const toml::node* n = find(k);
  if (!n) fail(k, "missing required key");
  return *n;
}

double Section::number_node(const toml::node& n, const std::string& k) const {
  if (const auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (const auto* f = n.as_floating_point()) {
    if (!std::isfinite(f->get()))
      scene_detail::fail(*file_, node_line(n), k, "expected a finite number, got " + describe(n));
    return f->get();
  }
  scene_detail::fail(*file_, node_line(n), k, "expected a number, got " + describe(n));
}

double Section::quantity_node(const toml::node& n, const std::string& k, QuantityKind kind) const {
  if (n.is_number()) return number_node(n, k);
  if (const auto* s = n.as_string()) {
    try {
      return parse_quantity(s->get(), kind);
    } catch (const UnitError& e) {
      scene_detail::fail(*file_, node_line(n), k, e.what());
    }
  }
  scene_detail::fail(*file_, node_line(n), k,
                     "expected " + quantity_expectation(kind) + ", got " + describe(n));
}

Vec2 Section::vector_node(const toml::node& n, const std::string& k,
                          std::optional<QuantityKind> kind) const {
  const auto* a = n.as_array();
  const std::string what = kind ? quantity_expectation(*kind) : std::string("a number");
  if (!a || a->size() != 2)
    scene_detail::fail(*file_, node_line(n), k,
                       "expected an array of 2 components, each " + what + ", got " + describe(n));
  Vec2 out;
  for (std::size_t d = 0; d < 2; ++d) {
    const std::string ek = k + "[" + std::to_string(d) + "]";
    out[static_cast<int>(d)] =
        kind ? quantity_node(*a->get(d), ek, *kind) : number_node(*a->get(d), ek);
  }
  return out;
}

double Section::quantity(std::string_view k, QuantityKind kind) const {
  const toml::node* n = find(k);
  if (!n) fail(k, "missing required key: expected " + quantity_expectation(kind));
  return quantity_node(*n, key(k), kind);
}

std::optional<double> Section::optional_quantity(std::string_view k, QuantityKind kind) const {
  const toml::node* n = find(k);
  if (!n) return std::nullopt;
  return quantity_node(*n, key(k), kind);
}

double Section::number(std::string_view k) const {
  const toml::node* n = find(k);
  if (!n) fail(k, "missing required key: expected a number");
  return number_node(*n, key(k));
}

std::optional<double> Section::optional_number(std::string_view k) const {
  const toml::node* n = find(k);
  if (!n) return std::nullopt;
  return number_node(*n, key(k));
}

long long Section::integer(std::string_view k) const {
  if (!has(k)) fail(k, "missing required key: expected an integer");
  return *optional_integer(k);
}

std::optional<long long> Section::optional_integer(std::string_view k) const {
  const toml::node* n = find(k);
  if (!n) return std::nullopt;
  if (const auto* i = n->as_integer()) return i->get();
  if (const auto* f = n->as_floating_point()) {
    const double v = f->get();
    if (std::isfinite(v) && v == std::floor(v) && std::abs(v) < 9e18)
      return static_cast<long long>(v);
  }
  expected(k, "an integer");
}

std::string Section::string(std::string_view k) const {
  const toml::node& n = require(k);
  if (const auto* s = n.as_string()) return s->get();
  expected(k, "a string");
}

std::optional<bool> Section::optional_bool(std::string_view k) const {
  const toml::node* n = find(k);
  if (!n) return std::nullopt;
  if (!n->is_boolean()) expected(k, "true or false");
  return n->as_boolean()->get();
}

std::optional<std::string> Section::optional_string(std::string_view k) const {
  if (!has(k)) return std::nullopt;
  return string(k);
}

std::string Section::name(std::string_view k) const {
  const std::string s = string(k);
  const bool ok = !s.empty() && std::all_of(s.begin(), s.end(), [](char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
  });
  if (!ok) expected(k, "a non-empty name of letters, digits, '_', '-' or '.'");
  return s;
}

Vec2 Section::vector(std::string_view k, std::optional<QuantityKind> kind) const {
  const toml::node* n = find(k);
  if (!n)
    fail(k, "missing required key: expected an array of 2 components, each " +
                (kind ? quantity_expectation(*kind) : std::string("a number")));
  return vector_node(*n, key(k), kind);
}

std::optional<Vec2> Section::optional_vector(std::string_view k,
                                             std::optional<QuantityKind> kind) const {
  const toml::node* n = find(k);
  if (!n) return std::nullopt;
  return vector_node(*n, key(k), kind);
}

std::vector<Vec2> Section::point_list(std::string_view k, QuantityKind kind) const {
  const toml::node& n = require(k);
  const auto* a = n.as_array();
  if (!a)
    expected(k, "an array of points [[x, y], ...], each coordinate " + quantity_expectation(kind));
  std::vector<Vec2> out;
  for (std::size_t i = 0; i < a->size(); ++i)
    out.push_back(vector_node(*a->get(i), key(k) + "[" + std::to_string(i) + "]", kind));
  return out;
}

std::vector<std::string> Section::string_list(std::string_view k) const {
  const toml::node& n = require(k);
  const auto* a = n.as_array();
  if (!a) expected(k, "an array of strings");
  std::vector<std::string> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    if (!e.is_string())
      scene_detail::fail(*file_, node_line(e), key(k) + "[" + std::to_string(i) + "]",
                         "expected a string, got " + describe(e));
    out.push_back(e.as_string()->get());
  }
  return out;
}

Section Section::table(std::string_view k) const {
  if (!has(k)) fail(k, "missing required table [" + key(k) + "]");
  return *optional_table(k);
}

std::optional<Section> Section::optional_table(std::string_view k) const {
  const toml::node* n = find(k);
  if (!n) return std::nullopt;
  if (const auto* t = n->as_table()) return Section(*t, key(k), *file_);
  expected(k, "a table");
}

std::vector<Section> Section::array_of_tables(std::string_view k, bool required) const {
  const toml::node* n = find(k);
  const std::string what = "at least one [[" + key(k) + "]] table";
  if (!n) {
    if (required) fail(k, "missing required key: expected " + what);
    return {};
  }
  const auto* a = n->as_array();
  if (!a || (required && a->empty())) expected(k, what);
  std::vector<Section> out;
  for (std::size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    const std::string path = key(k) + "[" + std::to_string(i) + "]";
    if (!e.is_table())
      scene_detail::fail(*file_, node_line(e), path, "expected a table, got " + describe(e));
    out.emplace_back(*e.as_table(), path, *file_);
  }
  return out;
}

}  // namespace scene_detail
}  // namespace fragmpm::pipeline
