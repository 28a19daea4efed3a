// The particle datasets of a frame or checkpoint group: every field of all_frame_fields with its
// units and description, and the reader that tolerates frames written without some of them.
#include <algorithm>
#include <string>
#include <vector>

#include "fragmpm/mpm/hdf5_io.hpp"
#include "fragmpm/mpm/run_file.hpp"
#include "run_file_fields.hpp"

namespace fragmpm::mpm {

using namespace run_file_detail;

template <int D>
Particles<D> read_particle_datasets(const h5::Group& g) {
  const std::size_t n = g.open_dataset("x").rows(), d = D;
  Particles<D> p;
  p.resize(n, g.exists("temperature"));
  // Fields not stored in the frame keep the defaults of Particles::resize.
  unpack<D>(read_shaped<double>(g, "x", {n, d}), p.x);
  if (g.exists("v")) unpack<D>(read_shaped<double>(g, "v", {n, d}), p.v);
  if (g.exists("F")) unpack<D>(read_shaped<double>(g, "F", {n, d, d}), p.F);
  if (g.exists("volume0")) p.volume0 = read_shaped<double>(g, "volume0", {n});
  if (g.exists("mass")) p.mass = read_shaped<double>(g, "mass", {n});
  if (g.exists("r1")) unpack_column<D>(read_shaped<double>(g, "r1", {n, d}), p.domain, 0);
  if (g.exists("r2")) unpack_column<D>(read_shaped<double>(g, "r2", {n, d}), p.domain, 1);
  if (g.exists("stress")) unpack<D>(read_shaped<double>(g, "stress", {n, d, d}), p.stress);
  if (g.exists("damage")) p.damage = read_shaped<double>(g, "damage", {n});
  if (g.exists("surface")) p.surface = read_shaped<std::uint8_t>(g, "surface", {n});
  if (g.exists("body")) p.body = read_shaped<std::int32_t>(g, "body", {n});
  if (g.exists("material")) p.material = read_shaped<std::int32_t>(g, "material", {n});
  if (g.exists("temperature")) p.temperature = read_shaped<double>(g, "temperature", {n});
  if (g.exists("id")) p.id = read_shaped<std::int32_t>(g, "id", {n});
  return p;
}

template <int D>
std::vector<std::string> write_particle_datasets(const h5::Group& g, const Particles<D>& particles,
                                                 const std::vector<std::string>& fields) {
  const std::size_t n = particles.size();
  std::vector<std::string> written;
  for (const std::string& field : all_frame_fields()) {
    // x and id are always written: a frame is the particles' positions, and id matches them to
    // the first frame when particles have left the domain.
    if (field != "x" && field != "id" && !fields.empty() &&
        std::find(fields.begin(), fields.end(), field) == fields.end())
      continue;
    if (field == "temperature" && particles.temperature.empty()) continue;
    if (field_size(particles, field) != n)
      throw RunFileError(g.describe("particle array for '" + field + "' has " +
                                    std::to_string(field_size(particles, field)) +
                                    " entries, expected " + std::to_string(n)));
    const h5::Dataset ds = write_field(g, particles, field);
    const FieldInfo info = field_info<D>(field);
    ds.set_attribute("units", info.units);
    ds.set_attribute("description", info.description);
    written.push_back(field);
  }
  return written;
}

template std::vector<std::string> write_particle_datasets<2>(const h5::Group&, const Particles<2>&,
                                                             const std::vector<std::string>&);
template std::vector<std::string> write_particle_datasets<3>(const h5::Group&, const Particles<3>&,
                                                             const std::vector<std::string>&);
template Particles<2> read_particle_datasets<2>(const h5::Group&);
template Particles<3> read_particle_datasets<3>(const h5::Group&);

}  // namespace fragmpm::mpm
