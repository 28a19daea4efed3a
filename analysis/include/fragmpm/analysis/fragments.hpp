#pragma once
// Fragments of a 2D run frame by union-find over the particle graph (docs/design.md).
//
// A particle is masked when d ≥ d_mask (fully damaged material belongs to no fragment) or when its
// position is not finite. Two particles p, q are joined when
//   * neither is masked and both belong to the same body (a fragment is a piece of one grain;
//   grains
//     that touch in the reference configuration stay apart),
//   * they were neighbours in the reference configuration: |X_p − X_q| ≤ reach_ref · ½(s0_p + s0_q)
//     with s0 = √V0 the reference spacing (1.5 takes the 8 lattice neighbours of a regular
//     arrangement, at distances s and √2 s, and not the next ring at 2 s),
//   * and they are still close now: |x_p − x_q| ≤ reach_now · ½(s_p + s_q) with s = √(V0 det F) the
//     local spacing.
// Fragments pressed together in the current configuration therefore stay distinct (they were never
// reference neighbours, or their bond was cut by the mask or by opening), which a picture-based
// count cannot do. Neighbours are found with a uniform bin grid over the reference positions
// (bins of the largest pair reach), so the cost is O(N log N), never O(N²).
//
// Fragments with fewer than `min_particles` particles are comminuted fines, reported apart from the
// resolved fragments. The default, 4, is one grid cell's worth of particles at the usual 2 × 2
// particles per cell: a smaller piece is below the resolution of the grid that computed it.
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fragmpm/mpm/particles.hpp"

namespace fragmpm::analysis {

struct FragmentOptions {
  double d_mask = 0.99;          ///< particles with d ≥ d_mask are masked, in (0, 1]
  double reference_reach = 1.5;  ///< reference-neighbour distance, in reference spacings
  double current_reach = 1.5;    ///< still-connected distance, in local current spacings
  int min_particles = 4;         ///< fragments with fewer particles are fines
};

/// Checks the options; throws std::invalid_argument naming the option and the accepted range.
void validate(const FragmentOptions& options);

struct FragmentLabels {
  /// Per particle: fragment id, or −1 when masked. Ids run 0 … count−1 in order of decreasing
  /// particle count (ties: by smallest particle index), so the fines come last.
  std::vector<std::int32_t> fragment;
  std::vector<std::int64_t> particles;  ///< per fragment: number of particles
  std::vector<std::uint8_t> fine;       ///< per fragment: 1 when below min_particles
  std::size_t masked = 0;               ///< number of masked particles

  std::size_t count() const { return particles.size(); }  ///< all fragments, fines included
  std::size_t fines() const;                              ///< fragments flagged fine
  std::size_t resolved() const { return count() - fines(); }
};

/// Labels the fragments of `current`, with `reference` (the run's first frame, same particles in
/// the same order) as the reference configuration. Needs x, volume0 and damage; uses F (current
/// area V0 det F) and body when present. Throws std::invalid_argument when the particle counts
/// differ or the options are out of range.
FragmentLabels label_fragments(const mpm::Particles<2>& reference, const mpm::Particles<2>& current,
                               const FragmentOptions& options = {});

/// Particle indices of every fragment, ascending within each fragment: result[f] for fragment f.
std::vector<std::vector<std::size_t>> fragment_members(const FragmentLabels& labels);

}  // namespace fragmpm::analysis
