#pragma once
// Kernel damage field and its gradient at the particles (001 eq. 17-19; 000 eq. 67), the Verlet
// neighbour lists it runs on (001 §2.5), and the node-level rules of damage-field-gradient
// partitioning: the nonlocal nodal gradient (001 Alg. 1; 000 eq. 69) and the field a particle maps
// to at a node (001 Alg. 2; 000 eq. 68).
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Verlet neighbour lists of particles over a uniform bin grid (001 §2.5).
///
/// A build lists, for every particle p, the particles q ≠ p with |x_p − x_q| ≤ r_list at build time,
/// where r_list = r_p (1 + f), r_p = `radius` and the skin f·r_p with f = `rebuild_fraction`. The
/// bins have edge r_list, so the listed q of p lie in the 3^D bins around p's bin.
///
/// Rebuild criterion (exact for the guarantee below). Let u_p = |x_p − x_p(build)| and u(1) ≥ u(2)
/// the two largest displacements since the build. For any pair, |x_p − x_q| ≥ |x_p − x_q|(build)
/// − u_p − u_q ≥ |x_p − x_q|(build) − (u(1) + u(2)), so a pair not listed (build distance > r_list)
/// is still farther apart than r_p as long as u(1) + u(2) ≤ f·r_p. `update` therefore rebuilds
/// exactly when u(1) + u(2) > f·r_p, and between rebuilds every pair closer than r_p is listed.
/// (The common "any particle moved more than f·r_p/2" rule is the same bound with u(2) ≤ u(1); it
/// rebuilds earlier when only a few particles move fast.) A change of particle count, radius or
/// fraction also rebuilds.
///
/// Neighbours of p are in ascending order of (bin, particle index), fixed by the positions alone:
/// lists do not depend on the thread count. After warm-up `update` allocates nothing unless a
/// rebuild needs more list entries than any earlier one.
///
/// Bins span the particles' bounding box; if that would need more than max(4N, 4096) bins (a few
/// fragments flying far apart), the bin edge grows until it does not — still correct, only slower.
template <int D>
class NeighbourLists {
 public:
  /// Rebuilds if needed (criterion above); returns true when it rebuilt. x: N positions [m];
  /// radius = kernel support r_p [m] (> 0); rebuild_fraction = f ≥ 0 (skin f·r_p). Throws
  /// std::invalid_argument for a bad radius or fraction or a non-finite position (naming the
  /// particle) and std::length_error for more than 2³² − 1 particles.
  bool update(const std::vector<Vec<D>>& x, double radius, double rebuild_fraction);
  /// Unconditional rebuild with the same arguments.
  void rebuild(const std::vector<Vec<D>>& x, double radius, double rebuild_fraction);

  /// Neighbours of particle p (excluding p), CSR rows: indices()[start()[p] .. start()[p + 1]).
  std::span<const std::uint32_t> neighbours(std::size_t p) const {
    return {indices_.data() + start_[p], start_[p + 1] - start_[p]};
  }
  const std::vector<std::size_t>& start() const { return start_; }       ///< N + 1 offsets
  const std::vector<std::uint32_t>& indices() const { return indices_; }  ///< listed q, by row
  std::size_t particle_count() const { return built_count_; }
  double radius() const { return radius_; }            ///< r_p of the last build [m]
  double list_radius() const { return list_radius_; }  ///< r_list = r_p (1 + f) [m]
  std::size_t builds() const { return builds_; }       ///< how many times rebuilt (logs, bench)

  /// Bin of particle p at the last build, and the bins around it: used by damage_field_gradient to
  /// skip particles with no damaged particle in reach.
  std::uint32_t bin_of(std::size_t p) const { return bin_of_[p]; }
  std::size_t bin_count() const { return bin_count_; }
  /// Calls visit(bin) for each existing bin among the 3^D around `bin`.
  template <class Visit>
  void for_each_adjacent_bin(std::uint32_t bin, Visit&& visit) const;

  /// Scratch of damage_field_gradient (one flag per bin); not part of the lists' state. Two
  /// concurrent damage_field_gradient calls must not share one NeighbourLists.
  std::vector<std::uint8_t>& bin_flags_scratch() const { return bin_flags_; }

 private:
  bool needs_rebuild(const std::vector<Vec<D>>& x, double radius, double rebuild_fraction);

  std::vector<std::size_t> start_{0};
  std::vector<std::uint32_t> indices_;
  std::vector<Vec<D>> built_x_;        // positions at the last build
  std::vector<std::uint32_t> bin_of_;  // bin of each particle at the last build
  std::vector<std::size_t> bin_start_; // CSR of particles per bin (bin_count + 1)
  std::vector<std::size_t> bin_cursor_;  // fill position per bin during the counting sort
  std::vector<std::uint32_t> binned_;  // particle indices sorted by bin, ascending within a bin
  std::vector<Vec<D>> binned_x_;       // their positions, contiguous per bin
  std::vector<std::vector<std::uint32_t>> thread_buffer_;
  std::vector<double> thread_top_;     // per thread: largest, second largest squared displacement
  std::vector<std::uint8_t> thread_bad_;
  mutable std::vector<std::uint8_t> bin_flags_;
  IVec<D> bin_dims_ = IVec<D>::Ones();
  std::size_t bin_count_ = 0;
  std::size_t built_count_ = 0;
  double radius_ = 0.0, fraction_ = 0.0, list_radius_ = 0.0;
  std::size_t builds_ = 0;
};

template <int D>
template <class Visit>
void NeighbourLists<D>::for_each_adjacent_bin(std::uint32_t bin, Visit&& visit) const {
  IVec<D> c;
  std::size_t rest = bin;
  for (int k = 0; k < D; ++k) {
    c[k] = static_cast<std::int64_t>(rest % static_cast<std::size_t>(bin_dims_[k]));
    rest /= static_cast<std::size_t>(bin_dims_[k]);
  }
  constexpr int combos = D == 2 ? 9 : 27;
  for (int combo = 0; combo < combos; ++combo) {
    std::int64_t linear = 0, stride = 1;
    int code = combo;
    bool inside = true;
    for (int k = 0; k < D; ++k) {
      const std::int64_t ck = c[k] + (code % 3) - 1;
      code /= 3;
      if (ck < 0 || ck >= bin_dims_[k]) {
        inside = false;
        break;
      }
      linear += ck * stride;
      stride *= bin_dims_[k];
    }
    if (inside) visit(static_cast<std::uint32_t>(linear));
  }
}

/// Kernel of 001 eq. (18): ω(r̄) = 1 − 3r̄² + 2r̄³ for 0 ≤ r̄ ≤ 1, else 0.
inline double damage_kernel(double rbar) {
  return rbar >= 1.0 ? 0.0 : 1.0 - rbar * rbar * (3.0 - 2.0 * rbar);
}

/// Normalised kernel damage field at the particles and its gradient (001 eq. 17-19; 000 eq. 67):
///   D̄(x_p) = Σ_q d̂_q ω(r̄_pq) / Σ_q ω(r̄_pq),  r̄_pq = |x_p − x_q| / r_p,
/// summed over q = p and the listed neighbours closer than r_p, and by the quotient rule
///   ∇D̄(x_p) = Σ_q (d̂_q − D̄_p) ∇ω_pq / Σ_q ω_pq,  ∇ω_pq = −6 (1 − r̄) (x_p − x_q) / r_p²
/// (ω'(r̄) = −6 r̄ (1 − r̄), and ∇r̄ = (x_p − x_q)/(r_p |x_p − x_q|)). Σ ω ≥ ω(0) = 1, so the field is
/// defined at every particle; normalisation makes D̄ = c exactly (to round-off) for constant d̂ = c,
/// also at free edges (001 Fig. 4c).
///
/// lists: updated for these x and this radius (every pair closer than r_p listed). x: N positions
/// [m]; dhat: N values d̂ = max(s, d) in [0, 1]; radius: r_p [m], normally the cell diagonal.
/// Output: field (N, D̄ at x_p) and gradient (N, ∇D̄ at x_p [1/m]), resized.
///
/// Work is skipped where it cannot matter: a particle with no d̂ ≠ 0 in the 3^D bins around its
/// bin gets D̄ = 0 and ∇D̄ = 0 without visiting its neighbours, and if every d̂ is zero the call is
/// one pass over dhat that writes zeros (the solver skips the call entirely in that case).
/// OpenMP over particles; each particle's sums run in list order, so the result does not depend on
/// the thread count. Allocates only when field/gradient grow.
template <int D>
void damage_field_gradient(const NeighbourLists<D>& lists, const std::vector<Vec<D>>& x,
                           const std::vector<double>& dhat, double radius, std::vector<double>& field,
                           std::vector<Vec<D>>& gradient);

// ---- Node-level rules of DFG partitioning --------------------------------------------------------

/// Order of 001 Alg. 1 line 5: true when particle gradient a replaces nodal gradient b, i.e. |a| >
/// |b|. Equal norms are broken lexicographically by the components (larger first), which makes the
/// nodal maximum a total order: the result of folding any set of particle gradients into a node does
/// not depend on the order (serial, coloured or per-thread-then-reduced P2G give the same node).
template <int D>
inline bool replaces_nodal_gradient(const Vec<D>& a, const Vec<D>& b) {
  const double na = a.squaredNorm(), nb = b.squaredNorm();
  if (na != nb) return na > nb;
  for (int k = 0; k < D; ++k)
    if (a[k] != b[k]) return a[k] > b[k];
  return false;
}

/// 001 Alg. 1 lines 5-7 for one particle–node pair: the nodal gradient (initially zero) becomes the
/// particle gradient of largest norm among the particles that map to the node (000 eq. 69 evaluated
/// at particle centres). Call for every entry of every particle's stencil.
template <int D>
inline void fold_nodal_gradient(const Vec<D>& particle_gradient, Vec<D>& nodal_gradient) {
  if (replaces_nodal_gradient<D>(particle_gradient, nodal_gradient)) nodal_gradient = particle_gradient;
}

/// 001 Alg. 2 line 3: field (0 or 1) that particle p uses at node i: 0 when ∇D̄_p · ∇D̄_i ≥ 0, else
/// 1. A zero gradient at either end gives field 0.
template <int D>
inline std::uint8_t particle_field_at_node(const Vec<D>& particle_gradient, const Vec<D>& nodal_gradient) {
  return particle_gradient.dot(nodal_gradient) >= 0.0 ? 0 : 1;
}

/// 001 Alg. 1 over all particles. Stencils as CSR: the nodes particle p maps to are
/// nodes[node_start[p] .. node_start[p + 1]) (linear node indices in [0, nodal_gradient.size()),
/// repeats allowed, e.g. CPDI corners sharing a node). particle_gradient: N ∇D̄_p [1/m].
/// nodal_gradient: pre-sized to the node count; overwritten with ∇D̄_i (zero at nodes no particle
/// maps to). Serial: the solver folds inside its own P2G loop with fold_nodal_gradient.
template <int D>
void nodal_damage_gradient(const std::vector<Vec<D>>& particle_gradient,
                           const std::vector<std::size_t>& node_start,
                           const std::vector<std::int64_t>& nodes, std::vector<Vec<D>>& nodal_gradient);

/// 001 Alg. 2 over all particles: field[e] ∈ {0, 1} of stencil entry e (particle p, node
/// nodes[e]), same CSR layout as nodal_damage_gradient; field is resized to nodes.size().
/// OpenMP over particles.
template <int D>
void particle_fields(const std::vector<Vec<D>>& particle_gradient, const std::vector<std::size_t>& node_start,
                     const std::vector<std::int64_t>& nodes, const std::vector<Vec<D>>& nodal_gradient,
                     std::vector<std::uint8_t>& field);

}  // namespace fragmpm::mpm
