// RAII layer over the HDF5 C API; see hdf5_io.hpp.
#include "fragmpm/mpm/hdf5_io.hpp"

#include <hdf5.h>

#include <filesystem>
#include <type_traits>
#include <utility>

namespace fragmpm::mpm::h5 {

static_assert(std::is_same_v<hid_t, std::int64_t>, "hdf5_io.hpp stores hid_t as std::int64_t");

namespace {

/// HDF5 prints its error stack to stderr by default; we report through exceptions instead. The
/// setting is per thread in thread-safe builds, so every entry point makes sure it holds here.
void silence_hdf5_errors() {
  thread_local bool done = false;
  if (!done) {
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
    done = true;
  }
}

/// The most specific message on HDF5's error stack (then cleared), to append to our own message.
std::string hdf5_detail() {
  std::string detail;
  H5Ewalk2(
      H5E_DEFAULT, H5E_WALK_UPWARD,
      [](unsigned n, const H5E_error2_t* error, void* data) -> herr_t {
        if (n == 0 && error->desc != nullptr) *static_cast<std::string*>(data) = error->desc;
        return 0;
      },
      &detail);
  H5Eclear2(H5E_DEFAULT);
  return detail;
}

/// Closes a temporary identifier (dataspace, datatype, property list, attribute) on scope exit.
class Temp {
 public:
  Temp(hid_t id, herr_t (*close)(hid_t)) : id_(id), close_(close) {}
  Temp(Temp&& other) noexcept : id_(std::exchange(other.id_, -1)), close_(other.close_) {}
  Temp(const Temp&) = delete;
  Temp& operator=(const Temp&) = delete;
  Temp& operator=(Temp&&) = delete;
  ~Temp() {
    if (id_ >= 0) close_(id_);
  }
  hid_t get() const { return id_; }
  bool ok() const { return id_ >= 0; }

 private:
  hid_t id_;
  herr_t (*close_)(hid_t);
};

template <Element T>
hid_t memory_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_NATIVE_DOUBLE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_NATIVE_FLOAT;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return H5T_NATIVE_INT32;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_NATIVE_INT64;
  else
    return H5T_NATIVE_UINT8;
}

/// Little-endian standard types in the file, so files are identical across platforms.
template <Element T>
hid_t file_type() {
  if constexpr (std::is_same_v<T, double>)
    return H5T_IEEE_F64LE;
  else if constexpr (std::is_same_v<T, float>)
    return H5T_IEEE_F32LE;
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return H5T_STD_I32LE;
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return H5T_STD_I64LE;
  else
    return H5T_STD_U8LE;
}

template <Element T>
const char* type_name() {
  if constexpr (std::is_same_v<T, double>)
    return "float64";
  else if constexpr (std::is_same_v<T, float>)
    return "float32";
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return "int32";
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return "int64";
  else
    return "uint8";
}

std::string join_path(const std::string& base, const std::string& name) {
  if (!name.empty() && name.front() == '/') return name;
  if (base.empty() || base == "/") return "/" + name;
  return base + "/" + name;
}

std::string dims_text(const Dims& dims) {
  std::string s = "(";
  for (std::size_t k = 0; k < dims.size(); ++k) s += (k ? "×" : "") + std::to_string(dims[k]);
  return s + ")";
}

/// Variable-length UTF-8 string type (h5py reads it as str, MATLAB as char).
Temp utf8_string_type() {
  Temp type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type.get(), H5T_VARIABLE);
  H5Tset_cset(type.get(), H5T_CSET_UTF8);
  return type;
}

Dims space_dims(hid_t space) {
  const int rank = H5Sget_simple_extent_ndims(space);
  if (rank <= 0) return {};
  std::vector<hsize_t> d(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space, d.data(), nullptr);
  return Dims(d.begin(), d.end());
}

}  // namespace

std::size_t element_count(const Dims& dims) {
  std::size_t n = 1;
  for (std::size_t d : dims) n *= d;
  return n;
}

// ---------------------------------------------------------------- Object

Object::Object(std::int64_t id, std::string file, std::string path)
    : id_(id), file_(std::move(file)), path_(std::move(path)) {
  silence_hdf5_errors();
}

Object::Object(Object&& other) noexcept
    : id_(std::exchange(other.id_, -1)),
      file_(std::move(other.file_)),
      path_(std::move(other.path_)) {}

Object& Object::operator=(Object&& other) noexcept {
  if (this != &other) {
    close();
    id_ = std::exchange(other.id_, -1);
    file_ = std::move(other.file_);
    path_ = std::move(other.path_);
  }
  return *this;
}

Object::~Object() {
  close();
}

void Object::close() noexcept {
  if (id_ < 0) return;
  switch (H5Iget_type(id_)) {
    case H5I_FILE:
      H5Fclose(id_);
      break;
    case H5I_GROUP:
      H5Gclose(id_);
      break;
    case H5I_DATASET:
      H5Dclose(id_);
      break;
    default:
      H5Oclose(id_);
      break;
  }
  id_ = -1;
}

std::string Object::describe(const std::string& what) const {
  return file_ + ": " + path_ + ": " + what;
}

namespace {
[[noreturn]] void fail(const Object& object, const std::string& what) {
  const std::string detail = hdf5_detail();
  throw RunFileError(object.describe(what) + (detail.empty() ? "" : " (HDF5: " + detail + ")"));
}
}  // namespace

namespace {
Temp open_attribute(const Object& object, const std::string& name) {
  silence_hdf5_errors();
  if (H5Aexists(object.id(), name.c_str()) <= 0) fail(object, "missing attribute '" + name + "'");
  Temp attribute(H5Aopen(object.id(), name.c_str(), H5P_DEFAULT), H5Aclose);
  if (!attribute.ok()) fail(object, "cannot open attribute '" + name + "'");
  Temp space(H5Aget_space(attribute.get()), H5Sclose);
  if (H5Sget_simple_extent_npoints(space.get()) != 1)
    fail(object, "attribute '" + name + "' is not a single value");
  return attribute;
}

void write_attribute(const Object& object, const std::string& name, hid_t file_type,
                     hid_t memory_type, const void* value) {
  silence_hdf5_errors();
  if (H5Aexists(object.id(), name.c_str()) > 0 && H5Adelete(object.id(), name.c_str()) < 0)
    fail(object, "cannot replace attribute '" + name + "'");
  Temp space(H5Screate(H5S_SCALAR), H5Sclose);
  Temp attribute(
      H5Acreate2(object.id(), name.c_str(), file_type, space.get(), H5P_DEFAULT, H5P_DEFAULT),
      H5Aclose);
  if (!attribute.ok() || H5Awrite(attribute.get(), memory_type, value) < 0)
    fail(object, "cannot write attribute '" + name + "'");
}
}  // namespace

void Object::set_attribute(const std::string& name, double value) const {
  write_attribute(*this, name, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, &value);
}

void Object::set_attribute(const std::string& name, std::int64_t value) const {
  write_attribute(*this, name, H5T_STD_I64LE, H5T_NATIVE_INT64, &value);
}

void Object::set_attribute(const std::string& name, const std::string& value) const {
  if (value.find('\0') != std::string::npos)
    throw RunFileError(describe("attribute '" + name + "' contains a NUL character"));
  const Temp type = utf8_string_type();
  const char* text = value.c_str();
  write_attribute(*this, name, type.get(), type.get(), &text);
}

void Object::set_attribute(const std::string& name, const char* value) const {
  set_attribute(name, std::string(value));
}

bool Object::has_attribute(const std::string& name) const {
  silence_hdf5_errors();
  const htri_t found = H5Aexists(id_, name.c_str());
  if (found < 0) fail(*this, "cannot query attribute '" + name + "'");
  return found > 0;
}

void Object::remove_attribute(const std::string& name) const {
  if (has_attribute(name) && H5Adelete(id_, name.c_str()) < 0)
    fail(*this, "cannot delete attribute '" + name + "'");
}

double Object::attribute_double(const std::string& name) const {
  const Temp attribute = open_attribute(*this, name);
  const Temp type(H5Aget_type(attribute.get()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_FLOAT && cls != H5T_INTEGER)
    fail(*this, "attribute '" + name + "' is not numeric");
  double value = 0.0;
  if (H5Aread(attribute.get(), H5T_NATIVE_DOUBLE, &value) < 0)
    fail(*this, "cannot read attribute '" + name + "'");
  return value;
}

std::int64_t Object::attribute_int64(const std::string& name) const {
  const Temp attribute = open_attribute(*this, name);
  const Temp type(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_INTEGER)
    fail(*this, "attribute '" + name + "' is not an integer");
  std::int64_t value = 0;
  if (H5Aread(attribute.get(), H5T_NATIVE_INT64, &value) < 0)
    fail(*this, "cannot read attribute '" + name + "'");
  return value;
}

std::string Object::attribute_string(const std::string& name) const {
  const Temp attribute = open_attribute(*this, name);
  const Temp type(H5Aget_type(attribute.get()), H5Tclose);
  if (H5Tget_class(type.get()) != H5T_STRING)
    fail(*this, "attribute '" + name + "' is not a string");
  if (H5Tis_variable_str(type.get()) > 0) {
    const Temp memory(H5Tcopy(H5T_C_S1), H5Tclose);
    H5Tset_size(memory.get(), H5T_VARIABLE);
    H5Tset_cset(memory.get(), H5Tget_cset(type.get()));
    char* text = nullptr;
    if (H5Aread(attribute.get(), memory.get(), &text) < 0)
      fail(*this, "cannot read attribute '" + name + "'");
    std::string value = text ? text : "";
    H5free_memory(text);
    return value;
  }
  // Fixed-length strings (written by other tools): read the bytes, drop NUL/space padding.
  const std::size_t size = H5Tget_size(type.get());
  std::string value(size, '\0');
  if (size > 0 && H5Aread(attribute.get(), type.get(), value.data()) < 0)
    fail(*this, "cannot read attribute '" + name + "'");
  value.resize(value.find('\0') == std::string::npos ? value.size() : value.find('\0'));
  if (H5Tget_strpad(type.get()) == H5T_STR_SPACEPAD) value.erase(value.find_last_not_of(' ') + 1);
  return value;
}

// ---------------------------------------------------------------- Group

bool Group::exists(const std::string& path) const {
  silence_hdf5_errors();
  if (path.empty() || path == "/" || path == ".") return true;
  // H5Lexists fails (rather than returning false) when an intermediate link is missing, so the
  // path is checked one component at a time.
  std::size_t start = path.front() == '/' ? 1 : 0;
  while (start <= path.size()) {
    const std::size_t slash = path.find('/', start);
    const std::string prefix = path.substr(0, slash);
    if (slash != start) {
      const htri_t found = H5Lexists(id(), prefix.c_str(), H5P_DEFAULT);
      if (found <= 0) {
        H5Eclear2(H5E_DEFAULT);
        return false;
      }
    }
    if (slash == std::string::npos) break;
    start = slash + 1;
  }
  // A dangling soft link exists as a link but not as an object.
  return H5Oexists_by_name(id(), path.c_str(), H5P_DEFAULT) > 0;
}

namespace {
H5I_type_t object_type(const Group& group, const std::string& path) {
  if (!group.exists(path)) return H5I_BADID;
  const hid_t object = H5Oopen(group.id(), path.c_str(), H5P_DEFAULT);
  if (object < 0) {
    H5Eclear2(H5E_DEFAULT);
    return H5I_BADID;
  }
  const H5I_type_t type = H5Iget_type(object);
  H5Oclose(object);
  return type;
}
}  // namespace

bool Group::is_group(const std::string& path) const {
  return object_type(*this, path) == H5I_GROUP;
}

bool Group::is_dataset(const std::string& path) const {
  return object_type(*this, path) == H5I_DATASET;
}

Group Group::open_group(const std::string& path) const {
  if (!is_group(path)) fail(*this, "no group '" + path + "'");
  const hid_t group = H5Gopen2(id(), path.c_str(), H5P_DEFAULT);
  if (group < 0) fail(*this, "cannot open group '" + path + "'");
  return Group(group, file_path(), join_path(object_path(), path));
}

Group Group::require_group(const std::string& path) const {
  if (exists(path)) return open_group(path);
  // One level at a time, each with the creation list below: groups HDF5 creates as intermediates
  // would get the default list, with modification times (see File::create).
  const std::size_t slash = path.find_last_of('/');
  if (slash != std::string::npos && slash > 0) (void)require_group(path.substr(0, slash));
  const Temp create(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  H5Pset_obj_track_times(create.get(), 0);  // see File::create
  const hid_t group = H5Gcreate2(id(), path.c_str(), H5P_DEFAULT, create.get(), H5P_DEFAULT);
  if (group < 0) fail(*this, "cannot create group '" + path + "'");
  return Group(group, file_path(), join_path(object_path(), path));
}

/// Creates the parent groups of a dataset path ("a/b/name" → "a/b") with require_group.
static void require_parent(const Group& g, const std::string& path) {
  const std::size_t slash = path.find_last_of('/');
  if (slash != std::string::npos && slash > 0) (void)g.require_group(path.substr(0, slash));
}

std::vector<std::string> Group::children() const {
  silence_hdf5_errors();
  H5G_info_t info;
  if (H5Gget_info(id(), &info) < 0) fail(*this, "cannot list the group");
  std::vector<std::string> names;
  names.reserve(info.nlinks);
  for (hsize_t k = 0; k < info.nlinks; ++k) {
    const ssize_t length =
        H5Lget_name_by_idx(id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, nullptr, 0, H5P_DEFAULT);
    if (length < 0) fail(*this, "cannot list the group");
    std::string name(static_cast<std::size_t>(length) + 1, '\0');
    H5Lget_name_by_idx(id(), ".", H5_INDEX_NAME, H5_ITER_INC, k, name.data(), name.size(),
                       H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(length));
    names.push_back(std::move(name));
  }
  return names;
}

void Group::remove(const std::string& path) const {
  if (!exists(path)) fail(*this, "cannot delete '" + path + "': no such object");
  if (H5Ldelete(id(), path.c_str(), H5P_DEFAULT) < 0) fail(*this, "cannot delete '" + path + "'");
}

Dataset Group::open_dataset(const std::string& path) const {
  if (!is_dataset(path)) fail(*this, "no dataset '" + path + "'");
  const hid_t dataset = H5Dopen2(id(), path.c_str(), H5P_DEFAULT);
  if (dataset < 0) fail(*this, "cannot open dataset '" + path + "'");
  return Dataset(dataset, file_path(), join_path(object_path(), path));
}

template <Element T>
Dataset Group::write(const std::string& path, const T* data, std::size_t count,
                     const Dims& dims) const {
  const std::string full = join_path(object_path(), path);
  if (count != element_count(dims))
    throw RunFileError(file_path() + ": " + full + ": " + std::to_string(count) +
                       " values do not fill the shape " + dims_text(dims));
  const std::vector<hsize_t> shape(dims.begin(), dims.end());
  if (exists(path)) {
    // Same type and shape: overwrite in place, so repeated checkpoints do not grow the file.
    if (is_dataset(path)) {
      Dataset existing = open_dataset(path);
      const Temp type(H5Dget_type(existing.id()), H5Tclose);
      const Temp plist(H5Dget_create_plist(existing.id()), H5Pclose);
      if (H5Tequal(type.get(), file_type<T>()) > 0 && existing.dims() == dims &&
          H5Pget_layout(plist.get()) != H5D_CHUNKED) {
        if (count > 0 &&
            H5Dwrite(existing.id(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
          fail(existing, "cannot write dataset");
        return existing;
      }
    }
    remove(path);
  }
  const Temp space(dims.empty()
                       ? H5Screate(H5S_SCALAR)
                       : H5Screate_simple(static_cast<int>(shape.size()), shape.data(), nullptr),
                   H5Sclose);
  require_parent(*this, path);
  const Temp links(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(links.get(), 1);
  const Temp create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_obj_track_times(create.get(), 0);  // see File::create
  const hid_t dataset = H5Dcreate2(id(), path.c_str(), file_type<T>(), space.get(), links.get(),
                                   create.get(), H5P_DEFAULT);
  if (dataset < 0) fail(*this, "cannot create dataset '" + path + "' " + dims_text(dims));
  Dataset result(dataset, file_path(), full);
  if (count > 0 && H5Dwrite(dataset, memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, data) < 0)
    fail(result, "cannot write dataset");
  return result;
}

template <Element T>
Array<T> Group::read(const std::string& path) const {
  return open_dataset(path).read<T>();
}

template <Element T>
Dataset Group::create_extendible(const std::string& path, const Dims& row_dims,
                                 std::size_t chunk_rows) const {
  if (exists(path)) remove(path);
  std::vector<hsize_t> shape{0}, max_shape{H5S_UNLIMITED}, chunk{chunk_rows > 0 ? chunk_rows : 1};
  for (std::size_t d : row_dims) {
    if (d == 0) fail(*this, "extendible dataset '" + path + "' needs non-empty rows");
    shape.push_back(d);
    max_shape.push_back(d);
    chunk.push_back(d);
  }
  const Temp space(H5Screate_simple(static_cast<int>(shape.size()), shape.data(), max_shape.data()),
                   H5Sclose);
  const Temp create(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_chunk(create.get(), static_cast<int>(chunk.size()), chunk.data());
  H5Pset_obj_track_times(create.get(), 0);  // see File::create
  require_parent(*this, path);
  const Temp links(H5Pcreate(H5P_LINK_CREATE), H5Pclose);
  H5Pset_create_intermediate_group(links.get(), 1);
  const hid_t dataset = H5Dcreate2(id(), path.c_str(), file_type<T>(), space.get(), links.get(),
                                   create.get(), H5P_DEFAULT);
  if (dataset < 0) fail(*this, "cannot create extendible dataset '" + path + "'");
  return Dataset(dataset, file_path(), join_path(object_path(), path));
}

// ---------------------------------------------------------------- Dataset

Dims Dataset::dims() const {
  const Temp space(H5Dget_space(id()), H5Sclose);
  if (!space.ok()) fail(*this, "cannot read the dataset's shape");
  return space_dims(space.get());
}

std::size_t Dataset::rows() const {
  const Dims d = dims();
  return d.empty() ? 1 : d.front();
}

template <Element T>
Array<T> Dataset::read() const {
  const Temp type(H5Dget_type(id()), H5Tclose);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_INTEGER && cls != H5T_FLOAT)
    fail(*this, std::string("is not numeric; expected ") + type_name<T>());
  if (std::is_integral_v<T> && cls == H5T_FLOAT)
    fail(*this, std::string("holds floating-point values; expected ") + type_name<T>());
  Array<T> result;
  result.dims = dims();
  result.values.resize(element_count(result.dims));
  if (!result.values.empty() &&
      H5Dread(id(), memory_type<T>(), H5S_ALL, H5S_ALL, H5P_DEFAULT, result.values.data()) < 0)
    fail(*this, "cannot read dataset");
  return result;
}

template <Element T>
void Dataset::append_rows(const T* data, std::size_t rows) const {
  if (rows == 0) return;
  Dims d = dims();
  if (d.empty()) fail(*this, "cannot append rows to a scalar dataset");
  std::vector<hsize_t> start(d.size(), 0), count(d.begin(), d.end()), extent(d.begin(), d.end());
  start[0] = d[0];
  count[0] = rows;
  extent[0] = d[0] + rows;
  if (H5Dset_extent(id(), extent.data()) < 0)
    fail(*this, "cannot extend dataset (is it extendible?)");
  const Temp file_space(H5Dget_space(id()), H5Sclose);
  H5Sselect_hyperslab(file_space.get(), H5S_SELECT_SET, start.data(), nullptr, count.data(),
                      nullptr);
  const Temp memory_space(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr),
                          H5Sclose);
  if (H5Dwrite(id(), memory_type<T>(), memory_space.get(), file_space.get(), H5P_DEFAULT, data) < 0)
    fail(*this, "cannot append rows");
}

void Dataset::set_rows(std::size_t rows) const {
  Dims d = dims();
  if (d.empty()) fail(*this, "cannot resize a scalar dataset");
  std::vector<hsize_t> extent(d.begin(), d.end());
  extent[0] = rows;
  if (H5Dset_extent(id(), extent.data()) < 0)
    fail(*this, "cannot resize dataset to " + std::to_string(rows) + " rows (is it extendible?)");
}

// ---------------------------------------------------------------- File

File File::create(const std::string& path, bool overwrite) {
  silence_hdf5_errors();
  std::error_code ec;
  if (!overwrite && std::filesystem::exists(path, ec))
    throw RunFileError(path + ": file exists; refusing to replace it without overwrite");
  const Temp access(H5Pcreate(H5P_FILE_ACCESS), H5Pclose);
  // The HDF5 1.8 file format: readable by every current tool (h5py, MATLAB, ParaView), and it
  // allows attributes larger than 64 KiB (dense attribute storage) for long scene texts.
  H5Pset_libver_bounds(access.get(), H5F_LIBVER_V18, H5F_LIBVER_V18);
  // No modification times in object headers: two runs of one scene then write the same bytes, so
  // that a sweep's members can be compared file for file (`cmp`) across schedulers and reruns.
  const Temp create(H5Pcreate(H5P_FILE_CREATE), H5Pclose);
  H5Pset_obj_track_times(create.get(), 0);
  const hid_t file =
      H5Fcreate(path.c_str(), overwrite ? H5F_ACC_TRUNC : H5F_ACC_EXCL, create.get(), access.get());
  if (file < 0) {
    const std::string detail = hdf5_detail();
    throw RunFileError(path + ": cannot create the file" +
                       (detail.empty() ? "" : " (HDF5: " + detail + ")"));
  }
  return File(file, path, "/");
}

File File::open(const std::string& path, bool writable) {
  silence_hdf5_errors();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw RunFileError(path + ": no such file");
  if (H5Fis_hdf5(path.c_str()) <= 0) {
    H5Eclear2(H5E_DEFAULT);
    throw RunFileError(path + ": not an HDF5 file");
  }
  const hid_t file = H5Fopen(path.c_str(), writable ? H5F_ACC_RDWR : H5F_ACC_RDONLY, H5P_DEFAULT);
  if (file < 0) {
    const std::string detail = hdf5_detail();
    throw RunFileError(path + ": cannot open the file" +
                       std::string(writable ? " for writing" : "") +
                       (detail.empty() ? "" : " (HDF5: " + detail + ")"));
  }
  return File(file, path, "/");
}

Group File::root() const {
  const hid_t group = H5Gopen2(id(), "/", H5P_DEFAULT);
  if (group < 0) fail(*this, "cannot open the root group");
  return Group(group, file_path(), "/");
}

void File::flush() const {
  if (H5Fflush(id(), H5F_SCOPE_GLOBAL) < 0) fail(*this, "cannot flush the file");
}

// ---------------------------------------------------------------- instantiations

#define FRAGMPM_H5_INSTANTIATE(T)                                                                 \
  template Dataset Group::write<T>(const std::string&, const T*, std::size_t, const Dims&) const; \
  template Array<T> Group::read<T>(const std::string&) const;                                     \
  template Dataset Group::create_extendible<T>(const std::string&, const Dims&, std::size_t)      \
      const;                                                                                      \
  template Array<T> Dataset::read<T>() const;                                                     \
  template void Dataset::append_rows<T>(const T*, std::size_t) const;

FRAGMPM_H5_INSTANTIATE(double)
FRAGMPM_H5_INSTANTIATE(float)
FRAGMPM_H5_INSTANTIATE(std::int32_t)
FRAGMPM_H5_INSTANTIATE(std::int64_t)
FRAGMPM_H5_INSTANTIATE(std::uint8_t)
#undef FRAGMPM_H5_INSTANTIATE

}  // namespace fragmpm::mpm::h5
