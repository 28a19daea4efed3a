#pragma once
// Private to the scene compiler: typed, unit-aware reading of TOML tables with errors that name
// file, line, key and what was expected.
#include <toml++/toml.h>

#include <initializer_list>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "fragmpm/mpm/types.hpp"
#include "fragmpm/pipeline/units.hpp"

namespace fragmpm::pipeline::scene_detail {

using Vec2 = mpm::Vec<2>;

/// Throws SceneError(file, line, key, detail).
[[noreturn]] void fail(const std::string& file, int line, const std::string& key,
                       const std::string& detail);

/// How a TOML value is shown after "got": strings quoted, numbers as written, "an array of 3
/// elements", "a table".
std::string describe(const toml::node& node);

/// "%g"-style formatting of an SI value with its unit, e.g. "0.0005 m".
std::string si(double value, std::string_view unit);

/// One TOML table with its dotted key path (e.g. "bodies[1]") and the file it came from.
class Section {
 public:
  Section(const toml::table& table, std::string path, const std::string& file);

  const std::string& path() const { return path_; }
  const std::string& file() const { return *file_; }
  int line() const;
  std::string key(std::string_view k) const;  ///< full dotted path of key k
  const toml::node* find(std::string_view k) const;
  bool has(std::string_view k) const { return find(k) != nullptr; }
  /// Line of k's value, or of the table itself when k is absent.
  int line_of(std::string_view k) const;

  /// Error about key k (at its value's line, or the table's line when absent).
  [[noreturn]] void fail(std::string_view k, const std::string& detail) const;
  /// Error about the whole table.
  [[noreturn]] void fail_table(const std::string& detail) const;
  /// "expected <what>, got <value of k>".
  [[noreturn]] void expected(std::string_view k, const std::string& what) const;

  /// Every key must be one of `allowed`; otherwise an "unknown key" error listing them.
  void allow_only(std::initializer_list<std::string_view> allowed) const;
  void allow_only(const std::vector<std::string_view>& allowed) const;

  double quantity(std::string_view k, QuantityKind kind) const;
  std::optional<double> optional_quantity(std::string_view k, QuantityKind kind) const;
  double number(std::string_view k) const;  ///< dimensionless TOML number (integer or float)
  std::optional<double> optional_number(std::string_view k) const;
  long long integer(
      std::string_view k) const;  ///< integer (a float with an integral value is accepted)
  std::optional<long long> optional_integer(std::string_view k) const;
  std::string string(std::string_view k) const;
  std::optional<std::string> optional_string(std::string_view k) const;
  std::optional<bool> optional_bool(std::string_view k) const;
  /// A name: non-empty, letters, digits, '_', '-', '.' only (names end up in HDF5 dataset names).
  std::string name(std::string_view k) const;
  /// [a, b] of quantities of `kind`, or of plain numbers when kind is empty.
  Vec2 vector(std::string_view k, std::optional<QuantityKind> kind) const;
  std::optional<Vec2> optional_vector(std::string_view k, std::optional<QuantityKind> kind) const;
  /// [[x, y], [x, y], ...] of quantities of `kind`.
  std::vector<Vec2> point_list(std::string_view k, QuantityKind kind) const;
  /// [a, b, ...] of strings.
  std::vector<std::string> string_list(std::string_view k) const;

  Section table(std::string_view k) const;
  std::optional<Section> optional_table(std::string_view k) const;
  /// [[k]] entries, with paths "k[0]", "k[1]", ...; required ones must have at least one entry.
  std::vector<Section> array_of_tables(std::string_view k, bool required) const;

 private:
  const toml::node& require(std::string_view k) const;
  double quantity_node(const toml::node& n, const std::string& key, QuantityKind kind) const;
  double number_node(const toml::node& n, const std::string& key) const;
  Vec2 vector_node(const toml::node& n, const std::string& key,
                   std::optional<QuantityKind> kind) const;

  const toml::table* table_;
  std::string path_;
  const std::string* file_;
};

}  // namespace fragmpm::pipeline::scene_detail
