#pragma once
// Kernel damage field and its gradient at the particles ([HH17] eq. (17)-(19); [XLS21] eq. (67)),
// the Verlet neighbour lists it runs on ([HH17] §2.5), and the node-level rules of
// damage-field-gradient partitioning: the nonlocal nodal gradient ([HH17] Alg. 1; [XLS21] eq. (69))
// and the field a particle maps to at a node ([HH17] Alg. 2; [XLS21] eq. (68)).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <span>
#include <vector>

#include "fragmpm/mpm/grid_index.hpp"
#include "fragmpm/mpm/types.hpp"

namespace fragmpm::mpm {

/// Verlet neighbour lists of particles over a uniform bin grid ([HH17] §2.5).
///
/// A build lists, for every particle p, the particles q ≠ p with |x_p − x_q| ≤ r_list at build
/// time, where r_list = r_p (1 + f), r_p = `radius` and the skin f·r_p with f = `rebuild_fraction`.
/// The bins have edge r_list/2 (a hair more), so the listed q of p lie within ±2 bins of p's bin
/// per direction: 5^D half-size bins hold 1.4× (2D) to 1.7× (3D) fewer candidates than 3^D bins
/// of edge r_list.
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
/// rebuild needs more list entries or bins than any earlier one.
///
/// Bins span the particles' bounding box; if that would need more than max(4N, 4096) bins (a few
/// fragments flying far apart), the bin edge grows until it does not — still correct, only slower.
template <int D>
class NeighbourLists {
 public:
  /// Listed neighbours of a particle lie within ±bin_reach bins of its bin in every direction.
  static constexpr int bin_reach = 2;

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
  const std::vector<std::size_t>& start() const { return start_; }        ///< N + 1 offsets
  const std::vector<std::uint32_t>& indices() const { return indices_; }  ///< listed q, by row
  std::size_t particle_count() const { return built_count_; }
  double radius() const { return radius_; }            ///< r_p of the last build [m]
  double list_radius() const { return list_radius_; }  ///< r_list = r_p (1 + f) [m]
  std::size_t builds() const { return builds_; }       ///< how many times rebuilt (logs, bench)
  std::size_t bin_count() const { return bin_count_; }

  /// Marks the particles that may have a listed neighbour q (or are themselves one) with
  /// value[q] ≠ 0: those whose bin lies within ±bin_reach bins of the bin of such a q (bins as at
  /// the last build). Returns false when every value is zero. O(N + bins); uses internal scratch,
  /// so two threads must not call it on one NeighbourLists at once. Read with near_marked(p).
  bool mark_near_nonzero(const std::vector<double>& value) const;
  bool near_marked(std::size_t p) const { return near_[bin_of_[p]] != 0; }

 private:
  /// Calls visit(first, last) for each row (direction 0) of existing bins among the (2 reach + 1)^D
  /// around `bin`: bins first … last are consecutive in the linear order, rows in ascending order.
  template <class Visit>
  void for_each_adjacent_row(std::uint32_t bin, Visit&& visit) const;
  bool needs_rebuild(const std::vector<Vec<D>>& x, double radius, double rebuild_fraction);

  std::vector<std::size_t> start_{0};
  std::vector<std::uint32_t> indices_;
  std::vector<Vec<D>> built_x_;          // positions at the last build
  std::vector<std::uint32_t> bin_of_;    // bin of each particle at the last build
  std::vector<std::size_t> bin_start_;   // CSR of particles per bin (bin_count + 1)
  std::vector<std::size_t> bin_cursor_;  // fill position per bin during the counting sort
  std::vector<std::uint32_t> binned_;    // particle indices sorted by bin, ascending within a bin
  std::vector<Vec<D>> binned_x_;         // their positions, contiguous per bin
  std::vector<std::vector<std::uint32_t>> thread_buffer_;
  std::vector<double> thread_top_;  // per thread: largest, second largest squared displacement
  std::vector<std::uint8_t> thread_bad_;
  mutable std::vector<std::uint8_t> near_, near_scratch_;  // mark_near_nonzero
  IVec<D> bin_dims_ = IVec<D>::Ones();
  std::size_t bin_count_ = 0;
  std::size_t built_count_ = 0;
  double radius_ = 0.0, fraction_ = 0.0, list_radius_ = 0.0;
  std::size_t builds_ = 0;
};

template <int D>
template <class Visit>
void NeighbourLists<D>::for_each_adjacent_row(std::uint32_t bin, Visit&& visit) const {
  IVec<D> c;
  std::size_t rest = bin;
  for (int k = 0; k < D; ++k) {
    c[k] = static_cast<std::int64_t>(rest % static_cast<std::size_t>(bin_dims_[k]));
    rest /= static_cast<std::size_t>(bin_dims_[k]);
  }
  constexpr int width = 2 * bin_reach + 1;
  const std::int64_t first_x = std::max<std::int64_t>(c[0] - bin_reach, 0);
  const std::int64_t last_x = std::min<std::int64_t>(c[0] + bin_reach, bin_dims_[0] - 1);
  constexpr int rows = D == 2 ? width : width * width;
  for (int row = 0; row < rows; ++row) {
    std::int64_t linear = 0, stride = bin_dims_[0];
    int code = row;
    bool inside = true;
    for (int k = 1; k < D; ++k) {
      const std::int64_t ck = c[k] + (code % width) - bin_reach;
      code /= width;
      if (ck < 0 || ck >= bin_dims_[k]) {
        inside = false;
        break;
      }
      linear += ck * stride;
      stride *= bin_dims_[k];
    }
    if (inside)
      visit(static_cast<std::size_t>(linear + first_x), static_cast<std::size_t>(linear + last_x));
  }
}

/// Kernel of [HH17] eq. (18): ω(r̄) = 1 − 3r̄² + 2r̄³ for 0 ≤ r̄ ≤ 1, else 0.
inline double damage_kernel(double rbar) {
  return rbar >= 1.0 ? 0.0 : 1.0 - rbar * rbar * (3.0 - 2.0 * rbar);
}

/// Normalised kernel damage field at the particles and its gradient ([HH17] eq. (17)-(19); [XLS21]
/// eq. (67)):
///   D̄(x_p) = Σ_q d̂_q ω(r̄_pq) / Σ_q ω(r̄_pq),  r̄_pq = |x_p − x_q| / r_p,
/// summed over q = p and the listed neighbours closer than r_p, and by the quotient rule
///   ∇D̄(x_p) = Σ_q (d̂_q − D̄_p) ∇ω_pq / Σ_q ω_pq,  ∇ω_pq = −6 (1 − r̄) (x_p − x_q) / r_p²
/// (ω'(r̄) = −6 r̄ (1 − r̄), and ∇r̄ = (x_p − x_q)/(r_p |x_p − x_q|)). Σ ω ≥ ω(0) = 1, so the field is
/// defined at every particle; normalisation makes D̄ = c exactly (to round-off) for constant d̂ = c,
/// also at free edges ([HH17] Fig. 4c).
///
/// lists: updated for these x and this radius (every pair closer than r_p listed). x: N positions
/// [m]; dhat: N values d̂ = max(s, d) in [0, 1]; radius: r_p [m], normally the cell diagonal.
/// Output: field (N, D̄ at x_p) and gradient (N, ∇D̄ at x_p [1/m]), resized.
///
/// Work is skipped where it cannot matter: a particle with no d̂ ≠ 0 within reach of its bin (see
/// NeighbourLists::mark_near_nonzero) gets D̄ = 0 and ∇D̄ = 0 without visiting its neighbours, and if
/// every d̂ is zero the call is one pass over dhat that writes zeros (the solver skips the call
/// entirely in that case). OpenMP over particles; each particle's sums run in list order, so the
/// result does not depend on the thread count. Allocates only when field/gradient grow.
template <int D>
void damage_field_gradient(const NeighbourLists<D>& lists, const std::vector<Vec<D>>& x,
                           const std::vector<double>& dhat, double radius,
                           std::vector<double>& field, std::vector<Vec<D>>& gradient);

// ---- Node-level rules of DFG partitioning ----

/// Order of [HH17] Alg. 1 line 5: true when particle gradient a replaces nodal gradient b, i.e. |a|
/// > |b|. Equal norms are broken lexicographically by the components (larger first), which makes
/// the nodal maximum a total order: the result of folding any set of particle gradients into a node
/// does not depend on the order (serial, coloured or per-thread-then-reduced P2G give the same
/// node).
template <int D>
inline bool replaces_nodal_gradient(const Vec<D>& a, const Vec<D>& b) {
  const double na = a.squaredNorm(), nb = b.squaredNorm();
  if (na != nb) return na > nb;
  for (int k = 0; k < D; ++k)
    if (a[k] != b[k]) return a[k] > b[k];
  return false;
}

/// [HH17] Alg. 1 lines 5-7 for one particle–node pair: the nodal gradient (initially zero) becomes
/// the particle gradient of largest norm among the particles that map to the node ([XLS21] eq. (69)
/// evaluated at particle centres). Call for every entry of every particle's stencil.
template <int D>
inline void fold_nodal_gradient(const Vec<D>& particle_gradient, Vec<D>& nodal_gradient) {
  if (replaces_nodal_gradient<D>(particle_gradient, nodal_gradient))
    nodal_gradient = particle_gradient;
}

/// Structure-tensor alternative to Alg. 1, closer to [HH17] §2.2's definition of the nonlocal nodal
/// gradient (the direction n* maximising ∫ |n*·∇D̄| over the node's neighbourhood): accumulate
/// T_i = Σ_p ∇D̄_p ⊗ ∇D̄_p over the particles mapping to node i (unweighted), and take its principal
/// eigenvector, which maximises Σ_p (n·∇D̄_p)². Gradients on the two sides of a crack are opposite
/// and reinforce instead of cancelling, and the average over the node's particles removes the
/// staircase error of a single particle: on the synthetic straight cracks of the tests the nodal
/// direction is within ~7° of the crack normal where Alg. 1 is off by up to ~18°. Cost: D(D+1)/2
/// additions per stencil entry and one small eigenproblem per node. Sums are order-dependent in
/// round-off only; the solver's fixed-order P2G keeps them thread-count independent.
template <int D>
inline void accumulate_gradient_tensor(const Vec<D>& particle_gradient, Mat<D>& tensor) {
  tensor.noalias() += particle_gradient * particle_gradient.transpose();
}

/// Principal direction of a nodal gradient tensor T (symmetric positive semi-definite), scaled by
/// √λ_max so that it has the units of a gradient [1/m]; zero for T = 0. The sign is arbitrary (only
/// signs of dot products with it are used) but a deterministic function of T; for an isotropic T
/// every direction is principal and e_0 is returned.
template <int D>
Vec<D> principal_gradient(const Mat<D>& tensor);

/// [HH17] Alg. 2 line 3: field (0 or 1) that particle p uses at node i: 0 when ∇D̄_p · ∇D̄_i ≥ 0,
/// else
/// 1. A zero gradient at either end gives field 0.
template <int D>
inline std::uint8_t particle_field_at_node(const Vec<D>& particle_gradient,
                                           const Vec<D>& nodal_gradient) {
  return particle_gradient.dot(nodal_gradient) >= 0.0 ? 0 : 1;
}

/// |cos| between ∇D̄_p and ∇D̄_i below which a surface-flagged particle's gradient carries no
/// side information at a node (the solver's junction rule, field_of). Where a free face ends at a
/// contact surface (the billet corner under the overhanging platen, P2 in docs/verification.md) the
/// junction particle's DFG points along the free face's normal, within a few degrees of the contact
/// plane (cos = −0.04 … 0.08 there), and the sign of ∇D̄_p · ∇D̄_i flips with round-off-sized changes
/// of the nodal direction. arcsin(0.2) ≈ 12°; the P2 error is the same for thresholds 0.1 to 0.3.
inline constexpr double ambiguous_gradient_cosine = 0.2;

/// Whether ∇D̄_p decides the field of particle p at node i by Alg. 2's sign test: it is further
/// than ambiguous_gradient_cosine from perpendicular to ∇D̄_i (false when either is zero).
template <int D>
inline bool gradient_decides_field(const Vec<D>& particle_gradient, const Vec<D>& nodal_gradient) {
  const double along = particle_gradient.dot(nodal_gradient);
  return along * along > ambiguous_gradient_cosine * ambiguous_gradient_cosine *
                             particle_gradient.squaredNorm() * nodal_gradient.squaredNorm();
}

/// Alg. 2 with a position fallback for particles out of reach of any damage (∇D̄_p = 0, which
/// plain Alg. 2 puts in field 0 whichever side of the crack they are on; with r_p = cell diagonal
/// this happens to the far particles of a CPDI or linear stencil at nodes on a crack). Such a
/// particle joins the side it lies on: the particles whose gradients agree with ∇D̄_i lie where
/// (x_p − x_i)·∇D̄_i < 0 (gradients point from intact material into the damage), so field 0 when
/// (x_p − x_i)·∇D̄_i ≤ 0, else 1. offset = x_p − x_i [m].
template <int D>
inline std::uint8_t particle_field_at_node(const Vec<D>& particle_gradient,
                                           const Vec<D>& nodal_gradient, const Vec<D>& offset) {
  if (particle_gradient.squaredNorm() > 0.0)
    return particle_field_at_node<D>(particle_gradient, nodal_gradient);
  return offset.dot(nodal_gradient) <= 0.0 ? 0 : 1;
}

/// [HH17] Alg. 1 over all particles. Stencils as CSR: the nodes particle p maps to are
/// nodes[node_start[p] .. node_start[p + 1]) (linear node indices in [0, nodal_gradient.size()),
/// repeats allowed, e.g. CPDI corners sharing a node). particle_gradient: N ∇D̄_p [1/m].
/// nodal_gradient: pre-sized to the node count; overwritten with ∇D̄_i (zero at nodes no particle
/// maps to). Serial: the solver folds inside its own P2G loop with fold_nodal_gradient.
template <int D>
void nodal_damage_gradient(const std::vector<Vec<D>>& particle_gradient,
                           const std::vector<std::size_t>& node_start,
                           const std::vector<std::int64_t>& nodes,
                           std::vector<Vec<D>>& nodal_gradient);

/// The structure-tensor nodal gradient over all particles (same CSR layout and output as
/// nodal_damage_gradient): ∇D̄_i = principal_gradient(Σ_p ∇D̄_p ⊗ ∇D̄_p). Serial; allocates
/// one tensor per node (a test/reference path; the solver accumulates in its P2G).
template <int D>
void nodal_damage_gradient_principal(const std::vector<Vec<D>>& particle_gradient,
                                     const std::vector<std::size_t>& node_start,
                                     const std::vector<std::int64_t>& nodes,
                                     std::vector<Vec<D>>& nodal_gradient);

/// [HH17] Alg. 2 over all particles: field[e] ∈ {0, 1} of stencil entry e (particle p, node
/// nodes[e]), same CSR layout as nodal_damage_gradient; field is resized to nodes.size().
/// OpenMP over particles.
template <int D>
void particle_fields(const std::vector<Vec<D>>& particle_gradient,
                     const std::vector<std::size_t>& node_start,
                     const std::vector<std::int64_t>& nodes,
                     const std::vector<Vec<D>>& nodal_gradient, std::vector<std::uint8_t>& field);

/// The same with the position fallback for ∇D̄_p = 0 (see particle_field_at_node); x: N particle
/// positions [m], grid: maps the linear node indices in `nodes` to positions.
template <int D>
void particle_fields(const std::vector<Vec<D>>& particle_gradient,
                     const std::vector<std::size_t>& node_start,
                     const std::vector<std::int64_t>& nodes,
                     const std::vector<Vec<D>>& nodal_gradient, const std::vector<Vec<D>>& x,
                     const GridIndex<D>& grid, std::vector<std::uint8_t>& field);

}  // namespace fragmpm::mpm
