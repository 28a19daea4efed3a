#include "fragmpm/mpm/aggregation_multigrid.hpp"

#include <omp.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <tuple>

namespace fragmpm::mpm {

namespace {

using RowMatrix = AggregationMultigrid::RowMatrix;

/// ⌊c / w⌋ for either sign, w = multigrid_aggregate_width: the coordinate of the aggregate that
/// holds node coordinate c.
inline std::int64_t aggregate_coordinate(std::int64_t c) {
  constexpr std::int64_t w = multigrid_aggregate_width;
  return c >= 0 ? c / w : -((w - 1 - c) / w);
}

/// λ_max(D⁻¹A), estimated from above. The smoother needs it from above: below λ_max its polynomial
/// amplifies the top of the spectrum, and the V-cycle is no longer positive definite (with a
/// power iteration's 10-step estimate, 10 % short on the bilaplacian model of the tests at
/// n = 257 even with a 10 % margin, the conjugate gradients stalled). Gershgorin's theorem bounds
/// it twice: max_i Σ_j |a_ij| / a_ii for D⁻¹A, and max_i Σ_j |a_ij| / √(a_ii a_jj) for the
/// similar D^(-1/2) A D^(-1/2). Both are exact for the Laplacian's and the bilaplacian's stencils,
/// but an open crack's rank-one history terms put the first far above λ_max (its ratios
/// |a_ij| / a_ii are those of the B-spline weights, up to 10² at a stencil's edge; on the cubic
/// plate's branched system it weakened the smoother and the prolongator until the iterations went
/// from 16 to 153) and the second, whose terms a positive semi-definite A keeps at most 1, still
/// about 1.6 times above (anisotropic cracked strip of the tests: 67.6 and 5.39 against 3.49;
/// the bench's cubic block: 8.41 and 4.91 against 3.03). So: the largest Ritz value of
/// `multigrid_lanczos_steps` Lanczos steps on D^(-1/2) A D^(-1/2), which approaches λ_max from
/// below far faster than a power iteration, with a 10 % margin, and never above either bound. The
/// start vector is fixed, so every run and thread count gets the same bits.
template <typename Matrix>
double largest_eigenvalue(const Matrix& A, const Eigen::VectorXd& inverse_diagonal) {
  const Eigen::Index n = A.rows();
  const Eigen::VectorXd scale = inverse_diagonal.cwiseSqrt();
  double bound = 0.0, scaled_bound = 0.0;
  // The largest of the rows' sums is the same whichever thread sums which row.
#pragma omp parallel for schedule(static) reduction(max : bound, scaled_bound)
  for (Eigen::Index i = 0; i < A.outerSize(); ++i) {
    double row = 0.0, scaled_row = 0.0;
    for (typename Matrix::InnerIterator it(A, i); it; ++it) {
      row += std::abs(it.value());
      scaled_row += std::abs(it.value()) * scale[it.index()];
    }
    bound = std::max(bound, row * inverse_diagonal[i]);
    scaled_bound = std::max(scaled_bound, scaled_row * scale[i]);
  }
  bound = std::min(bound, scaled_bound);
  if (!(bound > 0.0)) return 1.0;
  Eigen::VectorXd v(n), previous = Eigen::VectorXd::Zero(n), w(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v[i] = 1.0 + static_cast<double>((static_cast<std::uint64_t>(i) * 2654435761u) % 1024) / 1024.0;
  v.normalize();
  std::vector<double> alpha, beta;
  double last_beta = 0.0;
  for (int k = 0; k < multigrid_lanczos_steps && k < n; ++k) {
    w.noalias() = A * scale.cwiseProduct(v);
    w.array() *= scale.array();
    w -= last_beta * previous;
    alpha.push_back(w.dot(v));
    w -= alpha.back() * v;
    last_beta = w.norm();
    if (!(last_beta > 1e-12 * bound)) break;
    beta.push_back(last_beta);
    previous = v;
    v = w / last_beta;
  }
  const Eigen::Index m = static_cast<Eigen::Index>(alpha.size());
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(m, m);
  for (Eigen::Index i = 0; i < m; ++i) {
    T(i, i) = alpha[static_cast<std::size_t>(i)];
    if (i + 1 < m) T(i, i + 1) = T(i + 1, i) = beta[static_cast<std::size_t>(i)];
  }
  const double ritz = Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(T, Eigen::EigenvaluesOnly)
                          .eigenvalues()
                          .maxCoeff();
  return std::min(1.1 * ritz, bound);
}

/// left × right with the rows of the product split into one contiguous block per thread. Eigen's
/// sparse-sparse product runs on one thread, and the hierarchy's products per level (A T, A P and
/// Pᵀ (A P)) took about 6 % of the bench's cubic phase-field step on one thread, all of it
/// serial (`perf`, with the conversions around them another 3 %). Each row of the product depends
/// on the same row of `left` alone and is summed in the same order either way, so the blocks give
/// the whole product's rows bit for bit, on any number of threads.
template <typename Left>
RowMatrix row_parallel_product(const Left& left, const RowMatrix& right) {
  const Eigen::Index rows = left.rows();
  const int threads = static_cast<int>(std::min<Eigen::Index>(omp_get_max_threads(), rows / 1024));
  if (threads <= 1) return RowMatrix(left * right);
  std::vector<RowMatrix> parts(static_cast<std::size_t>(threads));
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    const Eigen::Index begin = rows * t / threads, end = rows * (t + 1) / threads;
    parts[static_cast<std::size_t>(t)] = left.middleRows(begin, end - begin) * right;
  }
  std::vector<Eigen::Index> first_row(parts.size() + 1, 0), first_entry(parts.size() + 1, 0);
  for (std::size_t t = 0; t < parts.size(); ++t) {
    first_row[t + 1] = first_row[t] + parts[t].rows();
    first_entry[t + 1] = first_entry[t] + parts[t].nonZeros();
  }
  RowMatrix product(rows, right.cols());
  product.resizeNonZeros(first_entry.back());
  int* outer = product.outerIndexPtr();
  outer[0] = 0;
  // Each block lands in its own rows and entries (the copy by one thread was 2 % of the cubic
  // bench row's samples on two threads).
#pragma omp parallel for schedule(static, 1) num_threads(threads)
  for (int t = 0; t < threads; ++t) {
    const RowMatrix& part = parts[static_cast<std::size_t>(t)];
    const Eigen::Index row = first_row[static_cast<std::size_t>(t)];
    const Eigen::Index at = first_entry[static_cast<std::size_t>(t)];
    std::copy_n(part.innerIndexPtr(), part.nonZeros(), product.innerIndexPtr() + at);
    std::copy_n(part.valuePtr(), part.nonZeros(), product.valuePtr() + at);
    for (Eigen::Index r = 0; r < part.rows(); ++r)
      outer[row + r + 1] = static_cast<int>(at + part.outerIndexPtr()[r + 1]);
  }
  return product;
}

}  // namespace

AggregationMultigrid::RowMap AggregationMultigrid::matrix(std::size_t level) const {
  if (level == 0)
    return RowMap(fine_rows_, fine_rows_, fine_nonzeros_, fine_outer_, fine_inner_, fine_values_);
  const RowMatrix& A = levels_[level].matrix;
  return RowMap(A.rows(), A.cols(), A.nonZeros(), A.outerIndexPtr(), A.innerIndexPtr(),
                A.valuePtr());
}

void AggregationMultigrid::build(Eigen::Index rows, Eigen::Index nonzeros, const int* outer,
                                 const int* inner, const double* values) {
  if (reuse_levels && levels_.size() > 1 && rows == fine_rows_) {
    fine_nonzeros_ = nonzeros;
    fine_outer_ = outer;
    fine_inner_ = inner;
    fine_values_ = values;
    const RowMap A = matrix(0);
    Level& level = levels_[0];
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < rows; ++i) {
      level.inverse_diagonal[i] = 1.0;
      for (RowMap::InnerIterator it(A, i); it; ++it)
        if (it.index() == i && it.value() > 0.0) level.inverse_diagonal[i] = 1.0 / it.value();
    }
    return;
  }
  fine_rows_ = rows;
  fine_nonzeros_ = nonzeros;
  fine_outer_ = outer;
  fine_inner_ = inner;
  fine_values_ = values;
  levels_.clear();
  levels_.emplace_back();
  levels_[0].coordinates = coordinates;
  levels_[0].fields = fields;
  if (static_cast<Eigen::Index>(levels_[0].coordinates.size()) != rows) {
    levels_[0].coordinates.assign(static_cast<std::size_t>(rows), {0, 0, 0});
    levels_[0].fields.assign(static_cast<std::size_t>(rows), 0);
  }
  for (std::size_t l = 0;; ++l) {
    const RowMap A = matrix(l);
    const Eigen::Index n = A.rows();
    {
      Level& level = levels_[l];
      level.inverse_diagonal.setOnes(n);
#pragma omp parallel for schedule(static)
      for (Eigen::Index i = 0; i < n; ++i)
        for (RowMap::InnerIterator it(A, i); it; ++it)
          if (it.index() == i && it.value() > 0.0) level.inverse_diagonal[i] = 1.0 / it.value();
      level.solution.setZero(n);
      level.rhs.setZero(n);
      level.residual.setZero(n);
      level.direction.setZero(n);
    }

    // Aggregates: the unknowns of one field whose coordinates agree after division by the width,
    // numbered in the order of their keys (so the coarse unknowns, like the fine ones, run in node
    // order).
    const std::vector<std::array<std::int64_t, 3>>& fine_coordinates = levels_[l].coordinates;
    const std::vector<std::int32_t>& fine_fields = levels_[l].fields;
    using Key = std::tuple<std::int32_t, std::int64_t, std::int64_t, std::int64_t>;
    auto key_of = [&](Eigen::Index i) {
      const auto& c = fine_coordinates[static_cast<std::size_t>(i)];
      return Key{fine_fields[static_cast<std::size_t>(i)], aggregate_coordinate(c[2]),
                 aggregate_coordinate(c[1]), aggregate_coordinate(c[0])};
    };
    std::vector<Key> keys(static_cast<std::size_t>(n));
#pragma omp parallel for schedule(static)
    for (Eigen::Index i = 0; i < n; ++i) keys[static_cast<std::size_t>(i)] = key_of(i);
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) {
      return keys[static_cast<std::size_t>(a)] < keys[static_cast<std::size_t>(b)];
    });
    std::vector<int> aggregate(static_cast<std::size_t>(n));
    std::vector<std::array<std::int64_t, 3>> coarse_coordinates;
    std::vector<std::int32_t> coarse_fields;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Key& key = keys[static_cast<std::size_t>(order[k])];
      if (k == 0 || key != keys[static_cast<std::size_t>(order[k - 1])]) {
        coarse_fields.push_back(std::get<0>(key));
        coarse_coordinates.push_back({std::get<3>(key), std::get<2>(key), std::get<1>(key)});
      }
      aggregate[static_cast<std::size_t>(order[k])] = static_cast<int>(coarse_fields.size()) - 1;
    }
    const Eigen::Index coarse = static_cast<Eigen::Index>(coarse_fields.size());

    // Small enough, or no longer coarsening (unknowns apart from one another): factorise, with
    // the relative diagonal shift that keeps the directions no particle sees off zero
    // (phase_field_state.hpp).
    if (n <= multigrid_coarsest_unknowns || 10 * coarse > 9 * n) {
      Eigen::SparseMatrix<double, Eigen::ColMajor, int> shifted = A;  // symmetric: rows = columns
      for (Eigen::Index i = 0; i < n; ++i) shifted.coeffRef(i, i) *= 1.0 + 1e-10;
      coarsest_.compute(shifted);
      break;
    }

    Level& level = levels_[l];
    level.largest_eigenvalue = largest_eigenvalue(A, level.inverse_diagonal);
    RowMatrix tentative(n, coarse);
    tentative.reserve(Eigen::VectorXi::Ones(n));
    for (Eigen::Index i = 0; i < n; ++i)
      tentative.insert(i, aggregate[static_cast<std::size_t>(i)]) = 1.0;
    tentative.makeCompressed();
    // P = T − ω D⁻¹ A T, formed in place: A T holds each row's own aggregate (A's diagonal), where
    // 1 + (−s) is the same number as 1 − s; the sparse difference, one thread, was 1 % of the
    // cubic bench row's samples on two.
    RowMatrix smoothing = row_parallel_product(A, tentative);
    const double damping = 4.0 / (3.0 * level.largest_eigenvalue);
    int missing_aggregate = 0;
#pragma omp parallel for schedule(static) reduction(max : missing_aggregate)
    for (Eigen::Index i = 0; i < n; ++i) {
      bool found = false;
      for (RowMatrix::InnerIterator it(smoothing, i); it; ++it) {
        it.valueRef() = -(it.value() * (damping * level.inverse_diagonal[i]));
        found = found || it.index() == aggregate[static_cast<std::size_t>(i)];
      }
      if (!found) missing_aggregate = 1;
    }
    if (missing_aggregate) {  // a row without its diagonal: T's 1 has no entry to go to
      level.prolongation = tentative + smoothing;
    } else {
#pragma omp parallel for schedule(static)
      for (Eigen::Index i = 0; i < n; ++i)
        for (RowMatrix::InnerIterator it(smoothing, i); it; ++it)
          if (it.index() == aggregate[static_cast<std::size_t>(i)]) it.valueRef() += 1.0;
      level.prolongation = std::move(smoothing);
    }
    level.restriction = level.prolongation.transpose();
    const RowMatrix product = row_parallel_product(A, level.prolongation);
    Level next;
    next.matrix = row_parallel_product(level.restriction, product);
    next.coordinates = std::move(coarse_coordinates);
    next.fields = std::move(coarse_fields);
    levels_.push_back(std::move(next));
  }
}

void AggregationMultigrid::smooth(std::size_t l, bool from_zero) const {
  const Level& level = levels_[l];
  const RowMap A = matrix(l);
  const double upper = level.largest_eigenvalue;
  const double lower = upper / multigrid_smoothing_range;
  const double centre = 0.5 * (upper + lower), half_width = 0.5 * (upper - lower);
  const double sigma = centre / half_width;
  double rho = 1.0 / sigma;
  Eigen::VectorXd& r = level.residual;
  Eigen::VectorXd& d = level.direction;
  Eigen::VectorXd& x = level.solution;
  if (from_zero) {
    r = level.rhs;
  } else {
    r = level.rhs;
    r.noalias() -= A * x;
  }
  d = level.inverse_diagonal.cwiseProduct(r) / centre;
  for (int k = 1; k <= multigrid_smoothing_degree; ++k) {
    if (from_zero && k == 1)
      x = d;
    else
      x += d;
    if (k == multigrid_smoothing_degree) break;
    r.noalias() -= A * d;
    const double rho_next = 1.0 / (2.0 * sigma - rho);
    d = (rho_next * rho) * d +
        (2.0 * rho_next / half_width) * level.inverse_diagonal.cwiseProduct(r);
    rho = rho_next;
  }
}

void AggregationMultigrid::cycle(std::size_t l) const {
  const Level& level = levels_[l];
  if (l + 1 == levels_.size()) {
    level.solution = coarsest_.solve(level.rhs);
    return;
  }
  const Level& next = levels_[l + 1];
  smooth(l, true);
  level.residual = level.rhs;
  level.residual.noalias() -= matrix(l) * level.solution;
  next.rhs.noalias() = level.restriction * level.residual;
  cycle(l + 1);
  level.solution.noalias() += level.prolongation * next.solution;
  smooth(l, false);
}

const Eigen::VectorXd& AggregationMultigrid::solve(const Eigen::VectorXd& residual) const {
  levels_[0].rhs = residual;
  cycle(0);
  return levels_[0].solution;
}

double AggregationMultigrid::operator_complexity() const {
  if (levels_.empty() || fine_nonzeros_ == 0) return 0.0;
  double sum = static_cast<double>(fine_nonzeros_);
  for (std::size_t l = 1; l < levels_.size(); ++l)
    sum += static_cast<double>(levels_[l].matrix.nonZeros());
  return sum / static_cast<double>(fine_nonzeros_);
}

double AggregationMultigrid::multiply_adds() const {
  double sum = 0.0;
  for (std::size_t l = 0; l + 1 < levels_.size(); ++l) {
    const Level& level = levels_[l];
    sum += 2.0 * static_cast<double>(matrix(l).nonZeros()) +
           static_cast<double>(level.prolongation.nonZeros() + level.restriction.nonZeros()) +
           6.0 * static_cast<double>(level.inverse_diagonal.size());
  }
  if (!levels_.empty())
    sum += 2.0 * static_cast<double>(coarsest_.matrixL().nestedExpression().nonZeros());
  return sum;
}

}  // namespace fragmpm::mpm
