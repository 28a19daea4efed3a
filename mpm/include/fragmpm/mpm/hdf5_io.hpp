#pragma once
// A small RAII layer over the HDF5 C API (libhdf5 1.10), shared by run files and grain files.
// Every failure throws RunFileError naming the file and the object path; HDF5's own error-stack
// printing is switched off and its innermost message is appended to ours instead.
//
// Arrays are row-major (C order), as HDF5, h5py and MATLAB's h5read (transposed) expect.
// Element types: double, float, int32, int64, uint8. Strings are variable-length UTF-8.
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace fragmpm::mpm {

/// Raised for unreadable, missing or inconsistent HDF5 files; the message names the file and
/// object.
struct RunFileError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

namespace h5 {

/// Element types the layer reads and writes.
template <class T>
concept Element = std::same_as<T, double> || std::same_as<T, float> ||
    std::same_as<T, std::int32_t> || std::same_as<T, std::int64_t> || std::same_as<T, std::uint8_t>;

using Dims = std::vector<std::size_t>;

/// Product of the dimensions (1 for a scalar, i.e. empty dims).
std::size_t element_count(const Dims& dims);

/// A dataset read into memory: row-major values and their dimensions.
template <Element T>
struct Array {
  std::vector<T> values;
  Dims dims;
};

/// An open HDF5 identifier (file, group or dataset) plus the names used in error messages.
/// Move-only; closes the identifier on destruction.
class Object {
 public:
  Object(Object&& other) noexcept;
  Object& operator=(Object&& other) noexcept;
  Object(const Object&) = delete;
  Object& operator=(const Object&) = delete;
  ~Object();

  std::int64_t id() const { return id_; }  ///< the raw hid_t, for direct C API calls
  const std::string& file_path() const { return file_; }
  const std::string& object_path() const { return path_; }  ///< "/" for the root group

  /// Attributes on this object. Setting replaces an existing attribute of the same name.
  void set_attribute(const std::string& name, double value) const;
  void set_attribute(const std::string& name, std::int64_t value) const;
  void set_attribute(const std::string& name, const std::string& value) const;
  void set_attribute(const std::string& name, const char* value) const;
  bool has_attribute(const std::string& name) const;
  void remove_attribute(const std::string& name) const;  ///< no-op when absent
  /// Readers throw RunFileError when the attribute is missing or of another kind. Integer
  /// attributes read as double are converted; floating attributes are not read as integers.
  double attribute_double(const std::string& name) const;
  std::int64_t attribute_int64(const std::string& name) const;
  std::string attribute_string(const std::string& name) const;

  /// "FILE: /object/path: what" — the format of every error this layer raises.
  std::string describe(const std::string& what) const;

 protected:
  Object(std::int64_t id, std::string file, std::string path);

 private:
  void close() noexcept;
  std::int64_t id_ = -1;
  std::string file_;
  std::string path_;
};

class Dataset;

/// A group (or the root group of a file). Paths are relative to this group ("a/b/c") or absolute.
class Group : public Object {
 public:
  bool exists(
      const std::string& path) const;  ///< true when every component of the link path exists
  bool is_group(const std::string& path) const;
  bool is_dataset(const std::string& path) const;
  Group open_group(const std::string& path) const;
  /// Creates the group and any missing intermediate groups; opens it if it already exists.
  Group require_group(const std::string& path) const;
  /// Names of the direct children (groups and datasets), sorted by name.
  std::vector<std::string> children() const;
  /// Deletes a link (group or dataset). The file does not shrink; HDF5 reuses the space later.
  void remove(const std::string& path) const;

  /// Writes a contiguous dataset of shape `dims` from `count` row-major values. An existing dataset
  /// of the same element type and shape is overwritten in place (no file growth); any other
  /// existing object of that name is replaced.
  template <Element T>
  Dataset write(const std::string& path, const T* data, std::size_t count, const Dims& dims) const;
  template <Element T>
  Dataset write(const std::string& path, const std::vector<T>& data, const Dims& dims) const;
  /// Reads a whole dataset, converting to T (integer→floating and integer→integer conversions are
  /// allowed; floating→integer is refused).
  template <Element T>
  Array<T> read(const std::string& path) const;
  Dataset open_dataset(const std::string& path) const;

  /// Creates an extendible dataset of shape (0, row_dims...) with unlimited first dimension,
  /// chunked by `chunk_rows` rows. Replaces an existing object of that name.
  template <Element T>
  Dataset create_extendible(const std::string& path, const Dims& row_dims,
                            std::size_t chunk_rows = 1024) const;

 protected:
  using Object::Object;
  friend class File;
};

class Dataset : public Object {
 public:
  Dims dims() const;
  std::size_t rows() const;  ///< first dimension (1 for a scalar dataset)
  template <Element T>
  Array<T> read() const;
  /// Appends `rows` rows (each of the dataset's row shape) from row-major `data`; the dataset must
  /// be extendible (see Group::create_extendible).
  template <Element T>
  void append_rows(const T* data, std::size_t rows) const;
  template <Element T>
  void append_rows(const std::vector<T>& data) const;
  /// Shrinks (or grows) the first dimension to `rows` (H5Dset_extent); extendible datasets only.
  void set_rows(std::size_t rows) const;

 protected:
  using Object::Object;
  friend class Group;
};

/// An open HDF5 file. Move-only; closes the file (after flushing) on destruction.
class File : public Object {
 public:
  /// Creates a new file. Refuses (RunFileError naming the path) to replace an existing file unless
  /// `overwrite` is set.
  static File create(const std::string& path, bool overwrite);
  /// Opens an existing file, read-only or read-write.
  static File open(const std::string& path, bool writable);

  Group root() const;
  void flush() const;  ///< H5Fflush: everything written so far reaches the disk

 protected:
  using Object::Object;
};

template <Element T>
Dataset Group::write(const std::string& path, const std::vector<T>& data, const Dims& dims) const {
  return write<T>(path, data.data(), data.size(), dims);
}

template <Element T>
void Dataset::append_rows(const std::vector<T>& data) const {
  const Dims d = dims();
  std::size_t row_size = 1;
  for (std::size_t k = 1; k < d.size(); ++k) row_size *= d[k];
  if (row_size == 0 || data.size() % row_size != 0)
    throw RunFileError(describe("append of " + std::to_string(data.size()) +
                                " values is not a whole number of rows"));
  append_rows<T>(data.data(), data.size() / row_size);
}

}  // namespace h5
}  // namespace fragmpm::mpm
