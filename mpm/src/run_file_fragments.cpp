// /fragments/ groups of a run file (run_file_fragments.hpp).
#include "fragmpm/mpm/run_file_fragments.hpp"

namespace fragmpm::mpm {

FragmentGroupWriter FragmentGroupWriter::open(const std::string& path) {
  return FragmentGroupWriter(h5::File::open(path, true));
}

void FragmentGroupWriter::replace(const std::string& name, const TableGroup& table) const {
  const h5::Group root = file_.root();
  const std::string path = "fragments/" + name;
  if (root.exists(path)) root.remove(path);
  const h5::Group g = root.require_group(path);
  for (const auto& [key, value] : table.attributes)
    std::visit([&, &key = key](const auto& v) { g.set_attribute(key, v); }, value);
  for (const TableColumn& c : table.columns) {
    const h5::Dataset ds = std::visit(
        [&](const auto& values) { return g.write(c.name, values, {values.size()}); }, c.values);
    ds.set_attribute("units", c.units);
    ds.set_attribute("description", c.description);
  }
}

void FragmentGroupWriter::flush() const {
  file_.flush();
}

}  // namespace fragmpm::mpm
