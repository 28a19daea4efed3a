// XDMF 3 writer for particle frames; see xdmf.hpp.
#include "fragmpm/mpm/xdmf.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fragmpm/mpm/hdf5_io.hpp"

namespace fragmpm::mpm {

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

namespace {

/// Shortest text that reads back as the same double.
std::string exact(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

const char* number_attributes(XdmfField::Number number) {
  switch (number) {
    case XdmfField::Number::int32:
      return R"(NumberType="Int" Precision="4")";
    case XdmfField::Number::uint8:
      return R"(NumberType="UChar" Precision="1")";
    default:
      return R"(NumberType="Float" Precision="8")";
  }
}

/// <DataItem> naming a whole HDF5 dataset.
std::string data_item(const std::string& dims, XdmfField::Number number,
                      const std::string& hdf_path, const std::string& indent) {
  return indent + "<DataItem Dimensions=\"" + dims + "\" " + number_attributes(number) +
         " Format=\"HDF\">" + xml_escape(hdf_path) + "</DataItem>\n";
}

/// <Attribute> of one field; vectors are N × 3 and tensors N × 3 × 3 datasets (see xdmf.hpp).
std::string attribute(const XdmfField& field, const std::string& n, const std::string& prefix,
                      const std::string& h5_reference) {
  const std::string hdf_path =
      field.dataset.empty() ? prefix + field.name : h5_reference + ":" + field.dataset;
  const char* type = "Scalar";
  std::string dims = n;
  if (field.kind == XdmfField::Kind::vector) {
    type = "Vector";
    dims += " 3";
  } else if (field.kind == XdmfField::Kind::tensor) {
    type = "Tensor";
    dims += " 3 3";
  }
  return "        <Attribute Name=\"" + xml_escape(field.name) + "\" AttributeType=\"" + type +
         "\" Center=\"Node\">\n" + data_item(dims, field.number, hdf_path, "          ") +
         "        </Attribute>\n";
}

}  // namespace

h5::Dataset write_padded_copy(const h5::Group& source, const h5::Group& target,
                              const std::string& name, XdmfField::Kind kind, double zz) {
  const h5::Array<double> in = source.read<double>(name);
  const std::size_t n = in.dims.empty() ? 0 : in.dims[0];
  const bool tensor = kind == XdmfField::Kind::tensor;
  const h5::Dims expected = tensor ? h5::Dims{n, 2, 2} : h5::Dims{n, 2};
  if (kind == XdmfField::Kind::scalar || in.dims != expected)
    throw RunFileError(
        source.describe("dataset '" + name + "' is not a 2D " + (tensor ? "tensor" : "vector")));
  std::vector<double> out(n * (tensor ? 9 : 3), 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    if (tensor) {
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) out[p * 9 + 3 * i + j] = in.values[p * 4 + 2 * i + j];
      out[p * 9 + 8] = zz;
    } else {
      out[p * 3] = in.values[p * 2];
      out[p * 3 + 1] = in.values[p * 2 + 1];
    }
  }
  h5::Dataset ds = target.write(name, out, tensor ? h5::Dims{n, 3, 3} : h5::Dims{n, 3});
  const h5::Dataset original = source.open_dataset(name);
  for (const char* a : {"units", "description"})
    if (original.has_attribute(a)) ds.set_attribute(a, original.attribute_string(a));
  return ds;
}

void write_xdmf(const std::string& xmf_path, const std::string& h5_reference, int dimension,
                const std::vector<XdmfFrame>& frames, const std::string& point_ids,
                std::size_t point_ids_length) {
  const std::string d = std::to_string(dimension);
  std::ostringstream out;
  out << "<?xml version=\"1.0\" encoding=\"utf-8\"?>\n"
      << "<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n"
      << "<Xdmf xmlns:xi=\"http://www.w3.org/2001/XInclude\" Version=\"3.0\">\n"
      << "  <Domain>\n"
      << "    <Grid Name=\"particles\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const XdmfFrame& frame : frames) {
    // Readers reject zero-sized point sets; an empty frame has nothing to show.
    if (frame.points == 0) continue;
    const std::string n = std::to_string(frame.points);
    const std::string name = frame.group.substr(frame.group.find_last_of('/') + 1);
    const std::string prefix = h5_reference + ":" + frame.group + "/";
    if (frame.points > point_ids_length)
      throw RunFileError(xmf_path + ": frame " + name + " has " + n + " points but " + point_ids +
                         " only " + std::to_string(point_ids_length) + " ids");
    const std::string ids = h5_reference + ":" + point_ids;
    out << "      <Grid Name=\"frame_" << xml_escape(name) << "\" GridType=\"Uniform\">\n"
        << "        <Time Value=\"" << exact(frame.time) << "\"/>\n"
        << "        <Topology TopologyType=\"Polyvertex\" NumberOfElements=\"" << n
        << "\" NodesPerElement=\"1\">\n";
    if (frame.points == point_ids_length) {
      out << data_item(n, XdmfField::Number::int32, ids, "          ");
    } else {
      out << "          <DataItem ItemType=\"HyperSlab\" Dimensions=\"" << n << "\" "
          << number_attributes(XdmfField::Number::int32) << ">\n"
          << "            <DataItem Dimensions=\"3 1\" NumberType=\"Int\" Format=\"XML\">0 1 " << n
          << "</DataItem>\n"
          << data_item(std::to_string(point_ids_length), XdmfField::Number::int32, ids,
                       "            ")
          << "          </DataItem>\n";
    }
    out << "        </Topology>\n"
        << "        <Geometry GeometryType=\"" << (dimension == 2 ? "XY" : "XYZ") << "\">\n"
        << data_item(n + " " + d, XdmfField::Number::float64, prefix + frame.geometry, "          ")
        << "        </Geometry>\n";
    // damage first: ParaView colours a newly opened file by its first point array.
    std::vector<const XdmfField*> fields;
    for (const XdmfField& field : frame.fields) fields.push_back(&field);
    std::stable_partition(fields.begin(), fields.end(),
                          [](const XdmfField* f) { return f->name == "damage"; });
    for (const XdmfField* field : fields) out << attribute(*field, n, prefix, h5_reference);
    out << "      </Grid>\n";
  }
  out << "    </Grid>\n  </Domain>\n</Xdmf>\n";

  const std::string temporary = xmf_path + ".tmp";
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << out.str();
    file.close();
    if (!file) throw RunFileError(temporary + ": cannot write the XDMF file");
  }
  std::error_code ec;
  std::filesystem::rename(temporary, xmf_path, ec);
  if (ec) throw RunFileError(xmf_path + ": cannot replace the XDMF file: " + ec.message());
}

}  // namespace fragmpm::mpm
