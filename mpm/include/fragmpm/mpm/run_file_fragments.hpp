#pragma once
// The /fragments/ groups of a run file: tables that an analysis computes in memory (named columns
// with units and descriptions, group attributes) and FragmentGroupWriter stores. The columns and
// their meaning belong to the analysis (analysis/fragment_tables.hpp); this side only knows how a
// table is laid out in HDF5: one 1-D dataset per column, `units` and `description` attributes on
// each.
#include <cstdint>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"

namespace fragmpm::mpm {

/// One dataset of a table group. `name` is relative to the group and may hold '/' ("table/area").
struct TableColumn {
  std::string name;
  std::string units;
  std::string description;
  std::variant<std::vector<double>, std::vector<std::int64_t>, std::vector<std::int32_t>> values;
};

using TableAttribute = std::variant<double, std::int64_t, std::string>;

/// A group's attributes (set in this order) and datasets.
struct TableGroup {
  std::vector<std::pair<std::string, TableAttribute>> attributes;
  std::vector<TableColumn> columns;
};

/// Opens a run file read-write to replace groups under /fragments; /meta, /frames and /series are
/// left untouched. Move-only.
class FragmentGroupWriter {
 public:
  /// Throws RunFileError when PATH cannot be opened for writing.
  static FragmentGroupWriter open(const std::string& path);
  /// Writes /fragments/NAME (NAME = "NNNNNN" or "series"), removing whatever was there first.
  void replace(const std::string& name, const TableGroup& group) const;
  void flush() const;

 private:
  explicit FragmentGroupWriter(h5::File file) : file_(std::move(file)) {}
  h5::File file_;
};

}  // namespace fragmpm::mpm
