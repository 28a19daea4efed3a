#pragma once
// XDMF 3 light-data file describing particle frames stored in an HDF5 file, so that ParaView
// (Xdmf3 and legacy Xdmf readers) and VisIt open them as a time series of Polyvertex point sets.
#include <cstddef>
#include <string>
#include <vector>

namespace fragmpm::mpm {

/// One per-point dataset of a frame group.
struct XdmfField {
  enum class Kind { scalar, vector, tensor };  ///< shapes N, N×D, N×D×D
  enum class Number { float64, int32, uint8 };
  std::string name;  ///< dataset name inside the frame group
  Kind kind = Kind::scalar;
  Number number = Number::float64;
};

/// One time step: a group holding an N×D position dataset and per-point fields.
struct XdmfFrame {
  std::string group;             ///< absolute HDF5 path, e.g. "/frames/000003"
  double time = 0.0;             ///< [s]
  std::size_t points = 0;        ///< N
  std::string geometry = "x";    ///< N×D float64 positions [m]
  std::vector<XdmfField> fields;
};

/// Writes the temporal collection to `xmf_path` (through a temporary file and a rename, so readers
/// never see a half-written file). `h5_reference` is how the XDMF file names the HDF5 file, normally
/// its file name relative to the .xmf. `point_ids` is the absolute path of a 1-D int32 dataset
/// holding 0, 1, …, `point_ids_length` − 1 (at least as long as the largest frame): ParaView's Xdmf3
/// reader builds no cells from a Polyvertex topology without connectivity, so every frame uses its
/// first N entries. 3D tensors are Tensor attributes, 2D ones Matrix attributes (N×2×2). Throws
/// RunFileError if it cannot write.
void write_xdmf(const std::string& xmf_path, const std::string& h5_reference, int dimension,
                const std::vector<XdmfFrame>& frames, const std::string& point_ids,
                std::size_t point_ids_length);

}  // namespace fragmpm::mpm
