// Neighbour lists, kernel damage field and the node-level DFG rules (see damage_field.hpp).
#include "fragmpm/mpm/damage_field.hpp"

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace fragmpm::mpm {

namespace {

/// Below this many particles the loops run on one thread: a parallel region costs more than the
/// work.
constexpr std::size_t parallel_threshold = 4096;

/// Thread t of n handles particles [first, last): contiguous chunks, so the CSR copy of each
/// thread's buffer lands at the offset of its first particle.
inline void chunk_of(std::size_t count, int thread, int threads, std::size_t& first,
                     std::size_t& last) {
  first = count * static_cast<std::size_t>(thread) / static_cast<std::size_t>(threads);
  last = count * static_cast<std::size_t>(thread + 1) / static_cast<std::size_t>(threads);
}

void check_arguments(std::size_t count, double radius, double rebuild_fraction) {
  if (!(radius > 0.0) || !std::isfinite(radius))
    throw std::invalid_argument("neighbour lists: radius must be a positive finite length, got " +
                                std::to_string(radius));
  if (!(rebuild_fraction >= 0.0) || !std::isfinite(rebuild_fraction))
    throw std::invalid_argument("neighbour lists: rebuild_fraction must be finite and >= 0, got " +
                                std::to_string(rebuild_fraction));
  if (count > std::numeric_limits<std::uint32_t>::max())
    throw std::length_error("neighbour lists: more than 2^32 - 1 particles (" +
                            std::to_string(count) + ")");
}

void check_csr(const char* who, std::size_t particles, const std::vector<std::size_t>& node_start,
               const std::vector<std::int64_t>& nodes, std::size_t node_count) {
  if (node_start.size() != particles + 1 || node_start.front() != 0 ||
      node_start.back() != nodes.size())
    throw std::invalid_argument(std::string(who) + ": node_start must have N + 1 = " +
                                std::to_string(particles + 1) + " entries from 0 to nodes.size()");
  for (const std::int64_t i : nodes)
    if (i < 0 || static_cast<std::size_t>(i) >= node_count)
      throw std::out_of_range(std::string(who) + ": node " + std::to_string(i) + " outside [0, " +
                              std::to_string(node_count) + ")");
}
}  // namespace

template <int D>
bool NeighbourLists<D>::needs_rebuild(const std::vector<Vec<D>>& x, double radius,
                                      double rebuild_fraction) {
  if (builds_ == 0 || x.size() != built_count_ || radius != radius_ ||
      rebuild_fraction != fraction_)
    return true;
  const std::size_t n = x.size();
  const int slots = omp_get_max_threads();
  if (thread_top_.size() < 2 * static_cast<std::size_t>(slots)) {
    thread_top_.resize(2 * static_cast<std::size_t>(slots));
    thread_bad_.resize(static_cast<std::size_t>(slots));
  }
  int used = 1;
#pragma omp parallel if (n >= parallel_threshold)
  {
    const int t = omp_get_thread_num();
    const int threads = omp_get_num_threads();
#pragma omp single
    used = threads;
    std::size_t first, last;
    chunk_of(n, t, threads, first, last);
    double top1 = 0.0, top2 = 0.0;  // squared displacements
    bool bad = false;
    for (std::size_t p = first; p < last; ++p) {
      const double u2 = (x[p] - built_x_[p]).squaredNorm();
      if (!std::isfinite(u2)) bad = true;
      if (u2 > top2) {
        if (u2 > top1) {
          top2 = top1;
          top1 = u2;
        } else {
          top2 = u2;
        }
      }
    }
    thread_top_[2 * static_cast<std::size_t>(t)] = top1;
    thread_top_[2 * static_cast<std::size_t>(t) + 1] = top2;
    thread_bad_[static_cast<std::size_t>(t)] = bad;
  }
  double top1 = 0.0, top2 = 0.0;
  for (int t = 0; t < used; ++t) {
    if (thread_bad_[static_cast<std::size_t>(t)]) return true;  // rebuild reports the bad particle
    for (int j = 0; j < 2; ++j) {
      const double u2 = thread_top_[2 * static_cast<std::size_t>(t) + static_cast<std::size_t>(j)];
      if (u2 > top2) {
        if (u2 > top1) {
          top2 = top1;
          top1 = u2;
        } else {
          top2 = u2;
        }
      }
    }
  }
  // u(1) + u(2) > f r_p: an unlisted pair may now be closer than r_p (see the header).
  return std::sqrt(top1) + std::sqrt(top2) > rebuild_fraction * radius;
}

template <int D>
bool NeighbourLists<D>::update(const std::vector<Vec<D>>& x, double radius,
                               double rebuild_fraction) {
  check_arguments(x.size(), radius, rebuild_fraction);
  if (!needs_rebuild(x, radius, rebuild_fraction)) return false;
  rebuild(x, radius, rebuild_fraction);
  return true;
}

template <int D>
void NeighbourLists<D>::rebuild(const std::vector<Vec<D>>& x, double radius,
                                double rebuild_fraction) {
  check_arguments(x.size(), radius, rebuild_fraction);
  const std::size_t n = x.size();
  // Bounding box; a non-finite position is named rather than binned (checked before any state
  // changes, so the lists stay as they were).
  Vec<D> lo = Vec<D>::Constant(std::numeric_limits<double>::infinity());
  Vec<D> hi = -lo;
  for (std::size_t p = 0; p < n; ++p) {
    if (!x[p].allFinite())
      throw std::invalid_argument("neighbour lists: particle " + std::to_string(p) +
                                  " has a non-finite position");
    lo = lo.cwiseMin(x[p]);
    hi = hi.cwiseMax(x[p]);
  }
  if (n == 0) lo = hi = Vec<D>::Zero();
  radius_ = radius;
  fraction_ = rebuild_fraction;
  list_radius_ = radius * (1.0 + rebuild_fraction);
  const double list_radius2 = list_radius_ * list_radius_;

  // Bins of edge ≥ r_list / bin_reach (the hair more keeps a pair at exactly r_list within reach
  // despite rounding of the bin coordinates); grow the edge if the box would need too many bins.
  const double bin_limit = std::min(std::max(4.0 * static_cast<double>(n), 4096.0),
                                    double(std::numeric_limits<std::uint32_t>::max()));
  double edge = list_radius_ / bin_reach * (1.0 + 1e-12);
  for (;;) {
    double total = 1.0;
    for (int k = 0; k < D; ++k) total *= std::floor((hi[k] - lo[k]) / edge) + 1.0;
    if (total <= bin_limit) break;
    edge *= std::max(1.01, std::pow(total / bin_limit, 1.0 / D));
  }
  const double inverse_edge = 1.0 / edge;
  bin_count_ = 1;
  for (int k = 0; k < D; ++k) {
    bin_dims_[k] = static_cast<std::int64_t>(std::floor((hi[k] - lo[k]) * inverse_edge)) + 1;
    bin_count_ *= static_cast<std::size_t>(bin_dims_[k]);
  }

  // Bin of each particle, then a stable counting sort (ascending particle index within a bin).
  bin_of_.resize(n);
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
  for (std::size_t p = 0; p < n; ++p) {
    std::size_t linear = 0, stride = 1;
    for (int k = 0; k < D; ++k) {
      auto c = static_cast<std::int64_t>((x[p][k] - lo[k]) * inverse_edge);
      c = std::clamp<std::int64_t>(c, 0, bin_dims_[k] - 1);
      linear += static_cast<std::size_t>(c) * stride;
      stride *= static_cast<std::size_t>(bin_dims_[k]);
    }
    bin_of_[p] = static_cast<std::uint32_t>(linear);
  }
  bin_start_.assign(bin_count_ + 1, 0);
  for (std::size_t p = 0; p < n; ++p) ++bin_start_[bin_of_[p] + 1];
  for (std::size_t b = 0; b < bin_count_; ++b) bin_start_[b + 1] += bin_start_[b];
  binned_.resize(n);
  binned_x_.resize(n);
  bin_cursor_.assign(bin_start_.begin(), bin_start_.end() - 1);
  for (std::size_t p = 0; p < n; ++p) {
    const std::size_t slot = bin_cursor_[bin_of_[p]]++;
    binned_[slot] = static_cast<std::uint32_t>(p);
    binned_x_[slot] = x[p];
  }

  // Lists: each thread scans its chunk of particles into its own buffer, then copies it into the
  // CSR at the offset of its first particle.
  start_.resize(n + 1);
  start_[0] = 0;
  const int slots = omp_get_max_threads();
  if (thread_buffer_.size() < static_cast<std::size_t>(slots))
    thread_buffer_.resize(static_cast<std::size_t>(slots));
#pragma omp parallel if (n >= parallel_threshold)
  {
    const int t = omp_get_thread_num();
    const int threads = omp_get_num_threads();
    std::size_t first, last;
    chunk_of(n, t, threads, first, last);
    std::vector<std::uint32_t>& buffer = thread_buffer_[static_cast<std::size_t>(t)];
    buffer.clear();
    for (std::size_t p = first; p < last; ++p) {
      const Vec<D> xp = x[p];
      const std::size_t before = buffer.size();
      // The bins of a row are consecutive, so their particles are one contiguous range.
      for_each_adjacent_row(bin_of_[p], [&](std::size_t first_bin, std::size_t last_bin) {
        for (std::size_t j = bin_start_[first_bin]; j < bin_start_[last_bin + 1]; ++j) {
          if ((binned_x_[j] - xp).squaredNorm() <= list_radius2 && binned_[j] != p)
            buffer.push_back(binned_[j]);
        }
      });
      start_[p + 1] = buffer.size() - before;  // count for now; offsets after the barrier
    }
#pragma omp barrier
#pragma omp single
    {
      for (std::size_t p = 0; p < n; ++p) start_[p + 1] += start_[p];
      indices_.resize(start_[n]);
    }
    std::copy(buffer.begin(), buffer.end(),
              indices_.begin() + static_cast<std::ptrdiff_t>(start_[first]));
  }

  built_x_.assign(x.begin(), x.end());
  built_count_ = n;
  ++builds_;
}

template <int D>
bool NeighbourLists<D>::mark_near_nonzero(const std::vector<double>& value) const {
  const std::size_t n = built_count_;
  if (value.size() != n)
    throw std::invalid_argument("mark_near_nonzero: " + std::to_string(value.size()) +
                                " values for lists of " + std::to_string(n) + " particles");
  near_.assign(bin_count_, 0);
  bool any = false;
  for (std::size_t p = 0; p < n; ++p)
    if (value[p] != 0.0) {
      near_[bin_of_[p]] = 1;
      any = true;
    }
  if (!any) return false;
  // Dilate by ±bin_reach bins, one direction at a time (a box dilation is separable).
  near_scratch_.resize(bin_count_);
  constexpr auto reach = static_cast<std::size_t>(bin_reach);
  std::size_t stride = 1;
  for (int k = 0; k < D; ++k) {
    const auto extent = static_cast<std::size_t>(bin_dims_[k]);
    near_scratch_.swap(near_);
    for (std::size_t b = 0; b < bin_count_; ++b) {
      const std::size_t ck = (b / stride) % extent;
      const std::size_t first = ck >= reach ? ck - reach : 0;
      const std::size_t last = std::min(ck + reach, extent - 1);
      std::uint8_t flag = 0;
      for (std::size_t c = first; c <= last; ++c)
        flag |= near_scratch_[b + c * stride - ck * stride];
      near_[b] = flag;
    }
    stride *= extent;
  }
  return true;
}

template <int D>
void damage_field_gradient(const NeighbourLists<D>& lists, const std::vector<Vec<D>>& x,
                           const std::vector<double>& dhat, double radius,
                           std::vector<double>& field, std::vector<Vec<D>>& gradient) {
  const std::size_t n = x.size();
  if (dhat.size() != n || lists.particle_count() != n)
    throw std::invalid_argument("damage_field_gradient: " + std::to_string(n) + " positions, " +
                                std::to_string(dhat.size()) + " damage values and lists of " +
                                std::to_string(lists.particle_count()) + " particles");
  if (!(radius > 0.0) || radius > lists.radius())
    throw std::invalid_argument("damage_field_gradient: radius " + std::to_string(radius) +
                                " m is not in (0, " + std::to_string(lists.radius()) +
                                "] m, the radius the neighbour lists were built for");
  field.resize(n);
  gradient.resize(n);

  if (!lists.mark_near_nonzero(dhat)) {
    std::fill(field.begin(), field.end(), 0.0);
    std::fill(gradient.begin(), gradient.end(), Vec<D>::Zero());
    return;
  }

  const double inverse_radius = 1.0 / radius;
  const double radius2 = radius * radius;
  const double gradient_factor = -6.0 * inverse_radius * inverse_radius;
#pragma omp parallel for schedule(dynamic, 256) if (n >= parallel_threshold)
  for (std::size_t p = 0; p < n; ++p) {
    if (!lists.near_marked(p)) {
      field[p] = 0.0;
      gradient[p] = Vec<D>::Zero();
      continue;
    }
    const Vec<D> xp = x[p];
    // Self term: ω(0) = 1, ∇ω(0) = 0.
    double sum_w = 1.0, sum_dw = dhat[p];
    Vec<D> grad_w = Vec<D>::Zero(), grad_dw = Vec<D>::Zero();
    for (const std::uint32_t q : lists.neighbours(p)) {
      const Vec<D> r = xp - x[q];
      const double r2 = r.squaredNorm();
      if (r2 >= radius2) continue;  // in the skin: ω = 0, ∇ω = 0
      const double rbar = std::sqrt(r2) * inverse_radius;
      const double w = 1.0 - rbar * rbar * (3.0 - 2.0 * rbar);  // [HH17] eq. (18)
      const Vec<D> gw = (gradient_factor * (1.0 - rbar)) * r;   // ∇_x ω at x_p
      const double d = dhat[q];
      sum_w += w;
      sum_dw += d * w;
      grad_w += gw;
      grad_dw += d * gw;
    }
    const double value = sum_dw / sum_w;  // [HH17] eq. (19): normalised by the kernel sum
    field[p] = value;
    gradient[p] = (grad_dw - value * grad_w) / sum_w;
  }
}

template <int D>
void nodal_damage_gradient(const std::vector<Vec<D>>& particle_gradient,
                           const std::vector<std::size_t>& node_start,
                           const std::vector<std::int64_t>& nodes,
                           std::vector<Vec<D>>& nodal_gradient) {
  const std::size_t n = particle_gradient.size();
  check_csr("nodal_damage_gradient", n, node_start, nodes, nodal_gradient.size());
  std::fill(nodal_gradient.begin(), nodal_gradient.end(), Vec<D>::Zero());  // Alg. 1 lines 1-3
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t e = node_start[p]; e < node_start[p + 1]; ++e)
      fold_nodal_gradient<D>(particle_gradient[p],
                             nodal_gradient[static_cast<std::size_t>(nodes[e])]);
}

template <int D>
Vec<D> principal_gradient(const Mat<D>& tensor) {
  if constexpr (D == 2) {
    // Closed form for [[a, b], [b, c]]: λ_max = (a + c)/2 + √(((a − c)/2)² + b²); (λ − c, b) and
    // (b, λ − a) are both eigenvectors, take the better conditioned one.
    const double a = tensor(0, 0), b = 0.5 * (tensor(0, 1) + tensor(1, 0)), c = tensor(1, 1);
    const double lambda = 0.5 * (a + c) + std::hypot(0.5 * (a - c), b);
    if (!(lambda > 0.0)) return Vec<D>::Zero();
    const Vec<D> v1(lambda - c, b), v2(b, lambda - a);
    const Vec<D>& v = v1.squaredNorm() >= v2.squaredNorm() ? v1 : v2;
    const double norm = v.norm();
    if (norm == 0.0) return Vec<D>(std::sqrt(lambda), 0.0);  // isotropic
    return (std::sqrt(lambda) / norm) * v;
  } else {
    Eigen::SelfAdjointEigenSolver<Mat<D>> solver;
    solver.computeDirect(0.5 * (tensor + tensor.transpose()));
    const double lambda = solver.eigenvalues()[D - 1];
    if (!(lambda > 0.0)) return Vec<D>::Zero();
    return std::sqrt(lambda) * solver.eigenvectors().col(D - 1);
  }
}

template <int D>
void nodal_damage_gradient_principal(const std::vector<Vec<D>>& particle_gradient,
                                     const std::vector<std::size_t>& node_start,
                                     const std::vector<std::int64_t>& nodes,
                                     std::vector<Vec<D>>& nodal_gradient) {
  check_csr("nodal_damage_gradient_principal", particle_gradient.size(), node_start, nodes,
            nodal_gradient.size());
  std::vector<Mat<D>> tensor(nodal_gradient.size(), Mat<D>::Zero());
  for (std::size_t p = 0; p < particle_gradient.size(); ++p)
    for (std::size_t e = node_start[p]; e < node_start[p + 1]; ++e)
      accumulate_gradient_tensor<D>(particle_gradient[p],
                                    tensor[static_cast<std::size_t>(nodes[e])]);
  for (std::size_t i = 0; i < tensor.size(); ++i)
    nodal_gradient[i] = principal_gradient<D>(tensor[i]);
}

template <int D>
void particle_fields(const std::vector<Vec<D>>& particle_gradient,
                     const std::vector<std::size_t>& node_start,
                     const std::vector<std::int64_t>& nodes,
                     const std::vector<Vec<D>>& nodal_gradient, std::vector<std::uint8_t>& field) {
  const std::size_t n = particle_gradient.size();
  check_csr("particle_fields", n, node_start, nodes, nodal_gradient.size());
  field.resize(nodes.size());
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t e = node_start[p]; e < node_start[p + 1]; ++e)
      field[e] = particle_field_at_node<D>(particle_gradient[p],
                                           nodal_gradient[static_cast<std::size_t>(nodes[e])]);
}

template <int D>
void particle_fields(const std::vector<Vec<D>>& particle_gradient,
                     const std::vector<std::size_t>& node_start,
                     const std::vector<std::int64_t>& nodes,
                     const std::vector<Vec<D>>& nodal_gradient, const std::vector<Vec<D>>& x,
                     const GridIndex<D>& grid, std::vector<std::uint8_t>& field) {
  const std::size_t n = particle_gradient.size();
  check_csr("particle_fields", n, node_start, nodes, nodal_gradient.size());
  if (x.size() != n)
    throw std::invalid_argument("particle_fields: " + std::to_string(x.size()) + " positions for " +
                                std::to_string(n) + " gradients");
  field.resize(nodes.size());
#pragma omp parallel for schedule(static) if (n >= parallel_threshold)
  for (std::size_t p = 0; p < n; ++p)
    for (std::size_t e = node_start[p]; e < node_start[p + 1]; ++e) {
      const std::int64_t i = nodes[e];
      field[e] = particle_field_at_node<D>(particle_gradient[p],
                                           nodal_gradient[static_cast<std::size_t>(i)],
                                           x[p] - grid.position(grid.global(i)));
    }
}

#define FRAGMPM_INSTANTIATE(D)                                                                     \
  template class NeighbourLists<D>;                                                                \
  template void damage_field_gradient<D>(const NeighbourLists<D>&, const std::vector<Vec<D>>&,     \
                                         const std::vector<double>&, double, std::vector<double>&, \
                                         std::vector<Vec<D>>&);                                    \
  template void nodal_damage_gradient<D>(const std::vector<Vec<D>>&,                               \
                                         const std::vector<std::size_t>&,                          \
                                         const std::vector<std::int64_t>&, std::vector<Vec<D>>&);  \
  template Vec<D> principal_gradient<D>(const Mat<D>&);                                            \
  template void nodal_damage_gradient_principal<D>(                                                \
      const std::vector<Vec<D>>&, const std::vector<std::size_t>&,                                 \
      const std::vector<std::int64_t>&, std::vector<Vec<D>>&);                                     \
  template void particle_fields<D>(const std::vector<Vec<D>>&, const std::vector<std::size_t>&,    \
                                   const std::vector<std::int64_t>&, const std::vector<Vec<D>>&,   \
                                   std::vector<std::uint8_t>&);                                    \
  template void particle_fields<D>(const std::vector<Vec<D>>&, const std::vector<std::size_t>&,    \
                                   const std::vector<std::int64_t>&, const std::vector<Vec<D>>&,   \
                                   const std::vector<Vec<D>>&, const GridIndex<D>&,                \
                                   std::vector<std::uint8_t>&);
FRAGMPM_INSTANTIATE(2)
FRAGMPM_INSTANTIATE(3)
#undef FRAGMPM_INSTANTIATE

}  // namespace fragmpm::mpm
