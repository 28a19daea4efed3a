#pragma once
// How particle arrays map to run-file datasets (docs/design.md): units, shapes and the copies
// between Eigen arrays of small matrices and row-major HDF5 buffers, and the layout code the writer
// (run_file.cpp) and the reader (run_file_reader.cpp) share. Private to mpm/src.
#include <string>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/mpm/particles.hpp"
#include "fragmpm/mpm/run_file.hpp"
#include "fragmpm/mpm/run_file_reader.hpp"
#include "fragmpm/mpm/xdmf.hpp"

namespace fragmpm::mpm::run_file_detail {

// ---- layout shared by RunFile and RunFileReader (run_file_reader.cpp)

/// Between a module's state and its reason in /meta modules: "name: on — reason".
inline constexpr const char* kModuleSeparator = " \u2014 ";

/// "000012": the name of frame 12 under /frames.
std::string frame_name(int index);
/// Lines of a newline-separated attribute (a trailing newline ends the last line).
std::vector<std::string> split_lines(const std::string& text);
/// The frame list of a /frames group (children named by digits only), sorted by index.
std::vector<FrameEntry> scan_frames(const h5::Group& frames);
/// /meta of a run file (every attribute RunFile::create writes must be there).
RunMeta read_meta(const h5::Group& meta);
/// Reads /frames/NNNNNN of `root`; RunFileError naming PATH and the group when it does not exist.
template <int D>
Particles<D> read_frame_group(const h5::Group& root, const std::string& path, int index,
                              std::size_t frame_count, double* time, long long* step);

/// Units (and a hint on layout) of every dataset, for users' own scripts.
struct FieldInfo {
  const char* units;
  const char* description;
  XdmfField::Kind kind;
  XdmfField::Number number;
};

template <int D>
FieldInfo field_info(const std::string& name) {
  using K = XdmfField::Kind;
  using N = XdmfField::Number;
  const bool plane = D == 2;
  if (name == "x") return {"m", "position, N x D", K::vector, N::float64};
  if (name == "v") return {"m/s", "velocity, N x D", K::vector, N::float64};
  if (name == "F")
    return {"1", "deformation gradient, N x D x D, F[p][i][j] = F_ij", K::tensor, N::float64};
  if (name == "volume0")
    return {plane ? "m^2 (per unit thickness)" : "m^3", "initial volume, N", K::scalar, N::float64};
  if (name == "mass")
    return {plane ? "kg/m (per unit thickness)" : "kg", "mass, N", K::scalar, N::float64};
  if (name == "r1")
    return {"m", "current domain edge vector r1 (F times the initial edge unless CPDI), N x D",
            K::vector, N::float64};
  if (name == "r2")
    return {"m", "current domain edge vector r2 (F times the initial edge unless CPDI), N x D",
            K::vector, N::float64};
  if (name == "stress")
    return {"Pa", "Cauchy stress, N x D x D, stress[p][i][j] = sigma_ij", K::tensor, N::float64};
  if (name == "damage") return {"1", "damage d in [0, 1], N", K::scalar, N::float64};
  if (name == "surface") return {"1", "1 = on a body boundary, N", K::scalar, N::uint8};
  if (name == "body") return {"1", "body id, N", K::scalar, N::int32};
  if (name == "material")
    return {"1", "index into the scene's material list, N", K::scalar, N::int32};
  if (name == "id")
    return {"1",
            "index of the particle at step 0, N (a run with [grid] outside = \"remove\" loses the "
            "particles that left the domain)",
            K::scalar, N::int32};
  return {"K", "temperature, N", K::scalar, N::float64};  // "temperature"
}

// ---- packing between Eigen arrays of structures and row-major HDF5 buffers

template <int D>
std::vector<double> pack(const std::vector<Vec<D>>& values) {
  std::vector<double> out(values.size() * D);
  for (std::size_t p = 0; p < values.size(); ++p)
    for (int i = 0; i < D; ++i) out[p * D + i] = values[p](i);
  return out;
}

/// N x D x D row-major: out[p][i][j] = m_p(i, j) (Eigen stores column-major, so copy explicitly).
template <int D>
std::vector<double> pack(const std::vector<Mat<D>>& values) {
  std::vector<double> out(values.size() * D * D);
  for (std::size_t p = 0; p < values.size(); ++p)
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) out[(p * D + i) * D + j] = values[p](i, j);
  return out;
}

template <int D>
std::vector<double> pack_column(const std::vector<Mat<D>>& values, int column) {
  std::vector<double> out(values.size() * D);
  for (std::size_t p = 0; p < values.size(); ++p)
    for (int i = 0; i < D; ++i) out[p * D + i] = values[p](i, column);
  return out;
}

/// Reads a dataset and checks its shape, so a foreign or damaged file gives a clear message.
template <h5::Element T>
std::vector<T> read_shaped(const h5::Group& group, const std::string& name,
                           const h5::Dims& expected) {
  h5::Array<T> array = group.read<T>(name);
  if (array.dims != expected) {
    auto text = [](const h5::Dims& dims) {
      std::string s;
      for (std::size_t k = 0; k < dims.size(); ++k) s += (k ? "x" : "") + std::to_string(dims[k]);
      return "(" + s + ")";
    };
    throw RunFileError(group.describe("dataset '" + name + "' has shape " + text(array.dims) +
                                      ", expected " + text(expected)));
  }
  return std::move(array.values);
}

template <int D>
void unpack(const std::vector<double>& in, std::vector<Vec<D>>& out) {
  for (std::size_t p = 0; p < out.size(); ++p)
    for (int i = 0; i < D; ++i) out[p](i) = in[p * D + i];
}

template <int D>
void unpack(const std::vector<double>& in, std::vector<Mat<D>>& out) {
  for (std::size_t p = 0; p < out.size(); ++p)
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) out[p](i, j) = in[(p * D + i) * D + j];
}

template <int D>
void unpack_column(const std::vector<double>& in, std::vector<Mat<D>>& out, int column) {
  for (std::size_t p = 0; p < out.size(); ++p)
    for (int i = 0; i < D; ++i) out[p](i, column) = in[p * D + i];
}

/// Particles::id, or 0 … N−1 for particles built without ids.
template <int D>
std::vector<std::int32_t> particle_ids(const Particles<D>& p) {
  if (!p.id.empty()) return p.id;
  std::vector<std::int32_t> ids(p.size());
  for (std::size_t k = 0; k < ids.size(); ++k) ids[k] = static_cast<std::int32_t>(k);
  return ids;
}

/// Number of entries of the particle array behind a frame field (to catch inconsistent input).
template <int D>
std::size_t field_size(const Particles<D>& p, const std::string& field) {
  if (field == "x") return p.x.size();
  if (field == "v") return p.v.size();
  if (field == "F") return p.F.size();
  if (field == "volume0") return p.volume0.size();
  if (field == "mass") return p.mass.size();
  if (field == "r1" || field == "r2") return p.domain.size();
  if (field == "stress") return p.stress.size();
  if (field == "damage") return p.damage.size();
  if (field == "surface") return p.surface.size();
  if (field == "body") return p.body.size();
  if (field == "material") return p.material.size();
  if (field == "id") return p.id.empty() ? p.size() : p.id.size();  // empty: the identity
  return p.temperature.size();
}

/// Writes one frame field; r1 and r2 are columns 0 and 1 of the CPDI domain matrix.
template <int D>
h5::Dataset write_field(const h5::Group& g, const Particles<D>& p, const std::string& field) {
  const std::size_t n = p.size(), d = D;
  if (field == "x") return g.write(field, pack<D>(p.x), {n, d});
  if (field == "v") return g.write(field, pack<D>(p.v), {n, d});
  if (field == "F") return g.write(field, pack<D>(p.F), {n, d, d});
  if (field == "volume0") return g.write(field, p.volume0, {n});
  if (field == "mass") return g.write(field, p.mass, {n});
  if (field == "r1") return g.write(field, pack_column<D>(p.domain, 0), {n, d});
  if (field == "r2") return g.write(field, pack_column<D>(p.domain, 1), {n, d});
  if (field == "stress") return g.write(field, pack<D>(p.stress), {n, d, d});
  if (field == "damage") return g.write(field, p.damage, {n});
  if (field == "surface") return g.write(field, p.surface, {n});
  if (field == "body") return g.write(field, p.body, {n});
  if (field == "material") return g.write(field, p.material, {n});
  if (field == "id") return g.write(field, particle_ids(p), {n});
  return g.write(field, p.temperature, {n});
}

}  // namespace fragmpm::mpm::run_file_detail
