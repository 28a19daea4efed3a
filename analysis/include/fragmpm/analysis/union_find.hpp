#pragma once
// Disjoint sets over the indices 0 … n−1 (union by size, path halving): near-constant time per
// operation, used to join particles into fragments (docs/design.md).
#include <cstddef>
#include <numeric>
#include <utility>
#include <vector>

namespace fragmpm::analysis {

struct UnionFind {
  std::vector<std::size_t> parent;
  std::vector<std::size_t> size;  ///< set size, valid at roots only

  explicit UnionFind(std::size_t n) : parent(n), size(n, 1) {
    std::iota(parent.begin(), parent.end(), std::size_t{0});
  }

  /// Representative of the set holding `a`.
  std::size_t find(std::size_t a) {
    while (parent[a] != a) {
      parent[a] = parent[parent[a]];  // path halving
      a = parent[a];
    }
    return a;
  }

  /// Joins the sets of `a` and `b`; returns false when they were already one set.
  bool unite(std::size_t a, std::size_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return false;
    if (size[a] < size[b]) std::swap(a, b);
    parent[b] = a;
    size[a] += size[b];
    return true;
  }

  std::size_t set_size(std::size_t a) { return size[find(a)]; }
};

}  // namespace fragmpm::analysis
