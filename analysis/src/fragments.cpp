// Fragment labelling by union-find over the particle graph; see fragments.hpp for the definition.
#include "fragmpm/analysis/fragments.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>
#include <string>
#include <utility>

#include "fragmpm/analysis/particle_domain.hpp"
#include "fragmpm/analysis/union_find.hpp"

namespace fragmpm::analysis {

void validate(const FragmentOptions& o) {
  if (!(o.d_mask > 0.0 && o.d_mask <= 1.0))
    throw std::invalid_argument("damage mask threshold d_mask must be in (0, 1], got " +
                                std::to_string(o.d_mask));
  if (!(o.reference_reach > 0.0) || !std::isfinite(o.reference_reach))
    throw std::invalid_argument(
        "reference neighbour reach must be a positive number of spacings, got " +
        std::to_string(o.reference_reach));
  if (!(o.current_reach > 0.0) || !std::isfinite(o.current_reach))
    throw std::invalid_argument(
        "current neighbour reach must be a positive number of spacings, got " +
        std::to_string(o.current_reach));
  if (o.min_particles < 1)
    throw std::invalid_argument("minimum particles per fragment must be at least 1, got " +
                                std::to_string(o.min_particles));
}

std::size_t FragmentLabels::fines() const {
  return static_cast<std::size_t>(std::count(fine.begin(), fine.end(), std::uint8_t{1}));
}

FragmentLabels label_fragments(const mpm::Particles<2>& reference, const mpm::Particles<2>& current,
                               const FragmentOptions& options) {
  validate(options);
  const std::size_t n = current.size();
  if (reference.size() != n)
    throw std::invalid_argument("the reference configuration has " +
                                std::to_string(reference.size()) +
                                " particles and the current one " + std::to_string(n) +
                                "; fragments need the same particles in both");
  if (current.damage.size() != n || current.volume0.size() != n || reference.volume0.size() != n)
    throw std::invalid_argument("fragment labelling needs damage and volume0 for every particle");

  FragmentLabels labels;
  labels.fragment.assign(n, -1);
  std::vector<std::size_t> active;  // unmasked particles
  std::vector<double> s0(n, 0.0), s(n, 0.0);
  for (std::size_t p = 0; p < n; ++p) {
    const bool finite = current.x[p].allFinite() && reference.x[p].allFinite();
    if (!finite || !(current.damage[p] < options.d_mask)) {
      ++labels.masked;
      continue;
    }
    active.push_back(p);
    s0[p] = std::sqrt(std::max(reference.volume0[p], 0.0));
    s[p] = particle_spacing(current, p);
  }

  UnionFind sets(n);
  if (!active.empty()) {
    // Uniform bins over the reference positions, of the largest pair reach: every reference
    // neighbour of p lies in p's bin or one of the 8 around it. Bins are kept as sorted keys, so
    // memory stays O(N) however sparse the particles are.
    double largest = 0.0;
    double xmin = reference.x[active[0]](0), ymin = reference.x[active[0]](1);
    for (const std::size_t p : active) {
      largest = std::max(largest, s0[p]);
      xmin = std::min(xmin, reference.x[p](0));
      ymin = std::min(ymin, reference.x[p](1));
    }
    const double bin = options.reference_reach * (largest > 0.0 ? largest : 1.0);
    double xmax = xmin, ymax = ymin;
    for (const std::size_t p : active) {
      xmax = std::max(xmax, reference.x[p](0));
      ymax = std::max(ymax, reference.x[p](1));
    }
    if (std::max(xmax - xmin, ymax - ymin) / bin > 1e9)
      throw std::invalid_argument(
          "the reference configuration spans more than 10^9 particle spacings; "
          "its positions or volumes are not those of one run");
    auto bin_of = [&](std::size_t p) {
      return std::pair<std::int64_t, std::int64_t>{
          static_cast<std::int64_t>(std::floor((reference.x[p](0) - xmin) / bin)),
          static_cast<std::int64_t>(std::floor((reference.x[p](1) - ymin) / bin))};
    };
    // Key = (bx, by) packed into one 64-bit integer (bins are non-negative and far below 2³¹).
    auto key = [](std::int64_t bx, std::int64_t by) { return (bx << 32) | (by & 0xffffffff); };
    std::vector<std::pair<std::int64_t, std::size_t>> keyed;
    keyed.reserve(active.size());
    for (const std::size_t p : active) {
      const auto [bx, by] = bin_of(p);
      keyed.emplace_back(key(bx, by), p);
    }
    std::sort(keyed.begin(), keyed.end());

    for (const std::size_t p : active) {
      const auto [bx, by] = bin_of(p);
      for (std::int64_t dx = -1; dx <= 1; ++dx) {
        for (std::int64_t dy = -1; dy <= 1; ++dy) {
          if (bx + dx < 0 || by + dy < 0) continue;
          const std::int64_t k = key(bx + dx, by + dy);
          auto it = std::lower_bound(keyed.begin(), keyed.end(),
                                     std::pair<std::int64_t, std::size_t>{k, 0});
          for (; it != keyed.end() && it->first == k; ++it) {
            const std::size_t q = it->second;
            if (q <= p || current.body[p] != current.body[q]) continue;
            const double reach0 = options.reference_reach * 0.5 * (s0[p] + s0[q]);
            if ((reference.x[p] - reference.x[q]).squaredNorm() > reach0 * reach0) continue;
            const double reach = options.current_reach * 0.5 * (s[p] + s[q]);
            if ((current.x[p] - current.x[q]).squaredNorm() > reach * reach) continue;
            sets.unite(p, q);
          }
        }
      }
    }
  }

  // Number the sets by decreasing size, ties by smallest particle index (the first one met).
  std::vector<std::size_t> roots;  // in order of first particle
  std::vector<std::int32_t> root_slot(n, -1);
  for (const std::size_t p : active) {
    const std::size_t r = sets.find(p);
    if (root_slot[r] < 0) {
      root_slot[r] = static_cast<std::int32_t>(roots.size());
      roots.push_back(r);
    }
  }
  std::vector<std::size_t> order(roots.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return sets.size[roots[a]] > sets.size[roots[b]];
  });
  std::vector<std::int32_t> id_of_slot(roots.size());
  labels.particles.resize(roots.size());
  labels.fine.resize(roots.size());
  for (std::size_t k = 0; k < order.size(); ++k) {
    id_of_slot[order[k]] = static_cast<std::int32_t>(k);
    const auto count = static_cast<std::int64_t>(sets.size[roots[order[k]]]);
    labels.particles[k] = count;
    labels.fine[k] = count < options.min_particles ? 1 : 0;
  }
  for (const std::size_t p : active)
    labels.fragment[p] = id_of_slot[static_cast<std::size_t>(root_slot[sets.find(p)])];
  return labels;
}

std::vector<std::vector<std::size_t>> fragment_members(const FragmentLabels& labels) {
  std::vector<std::vector<std::size_t>> members(labels.count());
  for (std::size_t f = 0; f < labels.count(); ++f)
    members[f].reserve(static_cast<std::size_t>(labels.particles[f]));
  for (std::size_t p = 0; p < labels.fragment.size(); ++p)
    if (labels.fragment[p] >= 0) members[static_cast<std::size_t>(labels.fragment[p])].push_back(p);
  return members;
}

}  // namespace fragmpm::analysis
