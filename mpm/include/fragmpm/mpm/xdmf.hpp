#pragma once
// XDMF 3 light-data file describing particle frames stored in an HDF5 file, so that ParaView
// (Xdmf3 and legacy Xdmf readers) and VisIt open them as a time series of Polyvertex point sets.
//
// Readers know vectors of 3 and tensors of 3 × 3 components only (Glyph and Tensor Glyph need
// them), so every vector attribute is an N × 3 dataset and every tensor an N × 3 × 3 one. A 3D
// run's frame datasets are that already; a 2D run keeps its N × 2 and N × 2 × 2 frame datasets as
// they are and the run file holds padded copies for the XDMF file beside them,
// /xdmf/frames/NNNNNN/<name> (write_padded_copy). XDMF Function items over the 2D datasets are no
// alternative: the XDMF 3 library's JOIN concatenates rather than interlaces, and it applies column
// hyperslabs in Fortran order. All attributes are Center="Node" on the Polyvertex topology;
// `damage` comes first, so ParaView colours by it when a run is opened.
#include <cstddef>
#include <string>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"

namespace fragmpm::mpm {

/// `text` with &, <, > and " escaped, for XML (and HTML) element content and attribute values.
std::string xml_escape(const std::string& text);

/// One per-point dataset of a frame.
struct XdmfField {
  enum class Kind { scalar, vector, tensor };  ///< shapes N, N×3, N×3×3 (see above)
  enum class Number { float64, int32, uint8 };
  std::string name;  ///< attribute name (the frame dataset's name)
  Kind kind = Kind::scalar;
  Number number = Number::float64;
  std::string dataset;  ///< absolute HDF5 path of the data; empty = <frame group>/<name>
};

/// One time step: a group holding an N×D position dataset and per-point fields.
struct XdmfFrame {
  std::string group;           ///< absolute HDF5 path, e.g. "/frames/000003"
  double time = 0.0;           ///< [s]
  std::size_t points = 0;      ///< N
  std::string geometry = "x";  ///< N×D float64 positions [m]
  std::vector<XdmfField> fields;
};

/// Writes the temporal collection to `xmf_path` (through a temporary file and a rename, so readers
/// never see a half-written file). `h5_reference` is how the XDMF file names the HDF5 file,
/// normally its file name relative to the .xmf. `point_ids` is the absolute path of a 1-D int32
/// dataset holding 0, 1, …, `point_ids_length` − 1 (at least as long as the largest frame):
/// ParaView's Xdmf3 reader builds no cells from a Polyvertex topology without connectivity, so
/// every frame uses its first N entries. Attributes are written with damage first, the others in
/// the order given. Throws RunFileError if it cannot write.
void write_xdmf(const std::string& xmf_path, const std::string& h5_reference, int dimension,
                const std::vector<XdmfFrame>& frames, const std::string& point_ids,
                std::size_t point_ids_length);

/// For 2D runs: writes TARGET/NAME, the N × 3 (vector) or N × 3 × 3 (tensor) copy of the N × 2 or
/// N × 2 × 2 float64 dataset SOURCE/NAME with the z components 0, except the zz entry of a tensor,
/// which is `zz` (1 for the plane-strain deformation gradient F; 0 for the stress, whose σ_zz the
/// run does not store). Copies `units` and `description`. Returns the dataset.
h5::Dataset write_padded_copy(const h5::Group& source, const h5::Group& target,
                              const std::string& name, XdmfField::Kind kind, double zz);

}  // namespace fragmpm::mpm
