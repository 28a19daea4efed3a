#include "fragmpm/mpm/aggregation_multigrid.hpp"

#include <algorithm>
#include <numeric>
#include <tuple>

namespace fragmpm::mpm {

namespace {

using RowMatrix = AggregationMultigrid::RowMatrix;

/// ⌊c / 2⌋ for either sign: the coordinate of the aggregate that holds node coordinate c.
inline std::int64_t halve(std::int64_t c) { return c >= 0 ? c / 2 : -((1 - c) / 2); }

/// λ_max(D⁻¹A) by power iteration from a fixed start (the same bits on every run and thread count;
/// D⁻¹A is similar to the symmetric D^(-1/2) A D^(-1/2), so its eigenvalues are real and ≥ 0).
/// The estimate approaches λ_max from below; the smoother's range allows 10 % above it.
template <typename Matrix>
double largest_eigenvalue(const Matrix& A, const Eigen::VectorXd& inverse_diagonal) {
  const Eigen::Index n = A.rows();
  Eigen::VectorXd v(n), w(n);
  for (Eigen::Index i = 0; i < n; ++i)
    v[i] = 1.0 + static_cast<double>((static_cast<std::uint64_t>(i) * 2654435761u) % 1024) / 1024.0;
  v.normalize();
  double estimate = 1.0;
  for (int k = 0; k < multigrid_power_iterations; ++k) {
    w.noalias() = A * v;
    w.array() *= inverse_diagonal.array();
    estimate = w.norm();
    if (!(estimate > 0.0)) return 1.0;
    v = w / estimate;
  }
  return estimate;
}

}  // namespace

AggregationMultigrid::RowMap AggregationMultigrid::matrix(std::size_t level) const {
  if (level == 0) return RowMap(fine_rows_, fine_rows_, fine_nonzeros_, fine_outer_, fine_inner_,
                                fine_values_);
  const RowMatrix& A = levels_[level].matrix;
  return RowMap(A.rows(), A.cols(), A.nonZeros(), A.outerIndexPtr(), A.innerIndexPtr(),
                A.valuePtr());
}

void AggregationMultigrid::build(Eigen::Index rows, Eigen::Index nonzeros, const int* outer,
                                 const int* inner, const double* values) {
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
      for (Eigen::Index i = 0; i < n; ++i)
        for (RowMap::InnerIterator it(A, i); it; ++it)
          if (it.index() == i && it.value() > 0.0) level.inverse_diagonal[i] = 1.0 / it.value();
      level.solution.setZero(n);
      level.rhs.setZero(n);
      level.residual.setZero(n);
      level.direction.setZero(n);
    }

    // Aggregates: the unknowns of one field whose coordinates agree after halving, numbered in
    // the order of their keys (so the coarse unknowns, like the fine ones, run in node order).
    const std::vector<std::array<std::int64_t, 3>>& fine_coordinates = levels_[l].coordinates;
    const std::vector<std::int32_t>& fine_fields = levels_[l].fields;
    using Key = std::tuple<std::int32_t, std::int64_t, std::int64_t, std::int64_t>;
    auto key_of = [&](Eigen::Index i) {
      const auto& c = fine_coordinates[static_cast<std::size_t>(i)];
      return Key{fine_fields[static_cast<std::size_t>(i)], halve(c[2]), halve(c[1]), halve(c[0])};
    };
    std::vector<int> order(static_cast<std::size_t>(n));
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return key_of(a) < key_of(b); });
    std::vector<int> aggregate(static_cast<std::size_t>(n));
    std::vector<std::array<std::int64_t, 3>> coarse_coordinates;
    std::vector<std::int32_t> coarse_fields;
    for (std::size_t k = 0; k < order.size(); ++k) {
      const Key key = key_of(order[k]);
      if (k == 0 || key != key_of(order[k - 1])) {
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
    for (Eigen::Index i = 0; i < n; ++i) tentative.insert(i, aggregate[static_cast<std::size_t>(i)]) = 1.0;
    tentative.makeCompressed();
    RowMatrix smoothing = A * tentative;
    const double damping = 4.0 / (3.0 * level.largest_eigenvalue);
    for (Eigen::Index i = 0; i < n; ++i)
      for (RowMatrix::InnerIterator it(smoothing, i); it; ++it)
        it.valueRef() *= damping * level.inverse_diagonal[i];
    level.prolongation = tentative - smoothing;
    level.restriction = level.prolongation.transpose();
    const RowMatrix product = A * level.prolongation;
    Level next;
    next.matrix = level.restriction * product;
    next.coordinates = std::move(coarse_coordinates);
    next.fields = std::move(coarse_fields);
    levels_.push_back(std::move(next));
  }
}

void AggregationMultigrid::smooth(std::size_t l, bool from_zero) const {
  const Level& level = levels_[l];
  const RowMap A = matrix(l);
  const double upper = 1.1 * level.largest_eigenvalue;
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
    d = (rho_next * rho) * d + (2.0 * rho_next / half_width) * level.inverse_diagonal.cwiseProduct(r);
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
