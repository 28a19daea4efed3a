// XDMF 3 writer for particle frames; see xdmf.hpp.
#include "fragmpm/mpm/xdmf.hpp"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "fragmpm/mpm/hdf5_io.hpp"

namespace fragmpm::mpm {
namespace {

std::string xml_escape(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      default: out += c;
    }
  }
  return out;
}

/// Shortest text that reads back as the same double.
std::string exact(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value);
  return buffer;
}

const char* number_attributes(XdmfField::Number number) {
  switch (number) {
    case XdmfField::Number::int32: return R"(NumberType="Int" Precision="4")";
    case XdmfField::Number::uint8: return R"(NumberType="UChar" Precision="1")";
    default: return R"(NumberType="Float" Precision="8")";
  }
}

/// <DataItem> naming a whole HDF5 dataset.
std::string data_item(const std::string& dims, XdmfField::Number number, const std::string& hdf_path,
                      const std::string& indent) {
  return indent + "<DataItem Dimensions=\"" + dims + "\" " + number_attributes(number) +
         " Format=\"HDF\">" + xml_escape(hdf_path) + "</DataItem>\n";
}

}  // namespace

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
          << data_item(std::to_string(point_ids_length), XdmfField::Number::int32, ids, "            ")
          << "          </DataItem>\n";
    }
    out << "        </Topology>\n"
        << "        <Geometry GeometryType=\"" << (dimension == 2 ? "XY" : "XYZ") << "\">\n"
        << data_item(n + " " + d, XdmfField::Number::float64, prefix + frame.geometry, "          ")
        << "        </Geometry>\n";
    for (const XdmfField& field : frame.fields) {
      const std::string hdf_path = prefix + field.name;
      const char* type = "Scalar";
      std::string dims = n;
      if (field.kind == XdmfField::Kind::vector) {
        type = "Vector";
        dims += " " + d;
      } else if (field.kind == XdmfField::Kind::tensor) {
        // The readers know only 3×3 tensors; a 2×2 one is a Matrix, which ParaView's Xdmf3 reader
        // shows as one 4-component array (xx, xy, yx, yy). Hyperslab components are not an option:
        // the XDMF 3 library applies multi-dimensional hyperslabs in Fortran order.
        type = dimension == 3 ? "Tensor" : "Matrix";
        dims += " " + d + " " + d;
      }
      out << "        <Attribute Name=\"" << xml_escape(field.name) << "\" AttributeType=\"" << type
          << "\" Center=\"Node\">\n"
          << data_item(dims, field.number, hdf_path, "          ") << "        </Attribute>\n";
    }
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
