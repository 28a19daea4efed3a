#include "fragmpm/analysis/crack_crossings.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace fragmpm::analysis {

double crack_length_across_rows(const mpm::Particles<2>& reference, const FragmentLabels& labels,
                                const RowWindow& window, double row_spacing) {
  if (labels.fragment.size() != reference.size())
    throw std::invalid_argument("crack_length_across_rows: labels for " +
                                std::to_string(labels.fragment.size()) + " particles, frame has " +
                                std::to_string(reference.size()));
  if (!(row_spacing > 0.0))
    throw std::invalid_argument("crack_length_across_rows: row spacing must be positive");
  std::map<long long, std::vector<std::size_t>> rows;  // reference row index → particles
  for (std::size_t p = 0; p < reference.size(); ++p) {
    if (reference.body[p] != window.body) continue;
    const double x = reference.x[p][0], y = reference.x[p][1];
    if (x < window.x_min || x > window.x_max || y < window.y_min || y > window.y_max) continue;
    // Centres sit half a spacing into their row (y = (k + ½) s), so floor never straddles a row.
    rows[static_cast<long long>(std::floor(y / row_spacing))].push_back(p);
  }
  long long crossings = 0;
  for (auto& [row, members] : rows) {
    std::sort(members.begin(), members.end(),
              [&](std::size_t a, std::size_t b) { return reference.x[a][0] < reference.x[b][0]; });
    bool in_masked = false;
    std::int32_t previous = -1;  // the last unmasked fragment of the row
    for (std::size_t p : members) {
      const std::int32_t fragment = labels.fragment[p];
      if (fragment < 0) {
        if (!in_masked) ++crossings;
        in_masked = true;
        continue;
      }
      if (!in_masked && previous >= 0 && fragment != previous) ++crossings;
      in_masked = false;
      previous = fragment;
    }
  }
  return static_cast<double>(crossings) * row_spacing;
}

}  // namespace fragmpm::analysis
