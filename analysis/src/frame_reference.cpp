#include "fragmpm/analysis/frame_reference.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace fragmpm::analysis {

FrameReference frame_reference(const mpm::Particles<2>& first, const mpm::Particles<2>& current) {
  if (current.size() > first.size())
    throw std::invalid_argument("the frame has " + std::to_string(current.size()) +
                                " particles, more than the " + std::to_string(first.size()) +
                                " of the first frame");
  // Row of each id in the first frame (ids are unique there: 0 … N−1 of the scene).
  std::vector<std::int64_t> row(first.size(), -1);
  for (std::size_t p = 0; p < first.size(); ++p) {
    const std::int32_t id = first.id[p];
    if (id < 0 || static_cast<std::size_t>(id) >= first.size() || row[id] >= 0)
      throw std::invalid_argument("the first frame's particle ids are not 0 … N−1 (particle " +
                                  std::to_string(p) + " has id " + std::to_string(id) + ")");
    row[static_cast<std::size_t>(id)] = static_cast<std::int64_t>(p);
  }
  FrameReference out;
  std::vector<std::uint8_t> present(first.size(), 0);
  std::vector<std::size_t> rows(current.size());
  for (std::size_t p = 0; p < current.size(); ++p) {
    const std::int32_t id = current.id[p];
    if (id < 0 || static_cast<std::size_t>(id) >= first.size())
      throw std::invalid_argument("particle " + std::to_string(p) + " has id " +
                                  std::to_string(id) + ", which the first frame does not hold");
    const std::size_t r = static_cast<std::size_t>(row[static_cast<std::size_t>(id)]);
    if (present[r])
      throw std::invalid_argument("particle id " + std::to_string(id) + " appears twice");
    present[r] = 1;
    rows[p] = r;
  }
  for (std::size_t r = 0; r < first.size(); ++r)
    if (!present[r]) {
      ++out.departed;
      out.departed_mass += first.mass[r];
    }
  out.particles = first.select(rows);
  return out;
}

}  // namespace fragmpm::analysis
