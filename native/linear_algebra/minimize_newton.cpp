#include "linear_algebra/minimize_newton.h"

#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <numeric>

#include "linear_algebra/armijo_backtracking.h"
#include "linear_algebra/sparse_cholesky.h"
#include "mesh/mesh.h"

namespace polycube {

namespace {

// The first diagonal shift, relative to the mean diagonal: the energies
// minimised here are invariant under translations (their Hessians are
// singular); the gradient has no part along them, so a shift this small
// leaves the step as it was. Multiplied by kShiftGrowth while a
// factorisation fails or its step does not descend.
constexpr double kFirstShift = 1e-9;
constexpr double kShiftGrowth = 100.0;
constexpr int kShiftTries = 6;

}  // namespace

// The lower triangle's pattern over the free unknowns, numbered in the
// order its factorisation eliminates them (`at`: each unknown's place), and
// where each element's entries land in its values. Why that order: the
// factorisation then takes the matrix as it is, where one in the unknowns'
// own order is copied, permuted, every time (CHOLMOD's factorisations: 7%
// of an untangling at scale; docs/design.md section 2.6, stage 7).
struct NewtonMinimizer::System {
  std::vector<int> element_unknowns;
  int element_size = 0, free = 0;
  std::vector<int> at;                 // per free unknown: its row and column in `matrix`
  Eigen::SparseMatrix<double> matrix;  // lower triangle
  std::vector<int> position;           // per element, K * K: index into matrix's values, or -1
  std::vector<int> diagonal;           // per free unknown: index of its diagonal entry
  SparseCholesky factor;
  bool analyzed = false;

  System(const std::vector<int>& unknowns, int k, int free_count)
      : element_unknowns(unknowns), element_size(k), free(free_count), at(free_count) {
    std::iota(at.begin(), at.end(), 0);
    build();
    // The elimination order of the pattern in the unknowns' order, then
    // the pattern again in it.
    SparseCholesky order;
    order.analyze(matrix, true);
    const Eigen::VectorXi& eliminated = order.ordering().indices();
    for (int place = 0; place < free; ++place) at[eliminated[place]] = place;
    build();
  }

  void build() {
    const int k = element_size;
    const std::vector<int>& unknowns = element_unknowns;
    const size_t elements = unknowns.size() / k;
    // Rows per column, counted then filled (a triplet list would hold
    // 36 entries per triangle at once).
    std::vector<int> start(free + 1, 0);
    auto for_each_pair = [&](auto&& visit) {
      for (size_t e = 0; e < elements; ++e) {
        const int* u = &unknowns[e * k];
        for (int q = 0; q < k; ++q)
          for (int p = 0; p < k; ++p)
            if (u[p] < free && u[q] < free && at[u[p]] >= at[u[q]]) visit(e, p, q, at[u[p]], at[u[q]]);
      }
    };
    for (int i = 0; i < free; ++i) ++start[i + 1];  // the diagonal, always
    for_each_pair([&](size_t, int, int, int, int column) { ++start[column + 1]; });
    std::partial_sum(start.begin(), start.end(), start.begin());
    std::vector<int> rows(start.back()), fill(start.begin(), start.end() - 1);
    for (int i = 0; i < free; ++i) rows[fill[i]++] = i;
    for_each_pair([&](size_t, int, int, int row, int column) { rows[fill[column]++] = row; });
    std::vector<int> outer(free + 1, 0), inner;
    inner.reserve(rows.size());
    for (int c = 0; c < free; ++c) {
      auto begin = rows.begin() + start[c], end = rows.begin() + start[c + 1];
      std::sort(begin, end);
      end = std::unique(begin, end);
      inner.insert(inner.end(), begin, end);
      outer[c + 1] = static_cast<int>(inner.size());
    }
    rows = {};
    std::vector<double> zeros(inner.size(), 0.0);
    matrix = Eigen::Map<const Eigen::SparseMatrix<double>>(free, free, static_cast<Eigen::Index>(inner.size()),
                                                           outer.data(), inner.data(), zeros.data());
    auto index_of = [&](int row, int column) {
      const int* first = inner.data() + outer[column];
      const int* last = inner.data() + outer[column + 1];
      return static_cast<int>(std::lower_bound(first, last, row) - inner.data());
    };
    position.assign(unknowns.size() * k, -1);
    for_each_pair(
        [&](size_t e, int p, int q, int row, int column) { position[e * k * k + q * k + p] = index_of(row, column); });
    diagonal.resize(free);
    for (int i = 0; i < free; ++i) diagonal[i] = index_of(at[i], at[i]);
  }

  // The system's solution for `rhs` (by unknown), by unknown.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const {
    Eigen::VectorXd placed(free);
    for (int i = 0; i < free; ++i) placed[at[i]] = rhs[i];
    const Eigen::VectorXd solution = factor.solve(placed);
    Eigen::VectorXd out(free);
    for (int i = 0; i < free; ++i) out[i] = solution[at[i]];
    return out;
  }

  bool same(const std::vector<int>& unknowns, int k, int free_count) const {
    return k == element_size && free_count == free && unknowns == element_unknowns;
  }

  // The assembled Hessian's values, without a shift: cleared, then each
  // block of elements' Hessians added in as the objective hands it over.
  void clear() {
    double* values = matrix.valuePtr();
    std::fill(values, values + matrix.nonZeros(), 0.0);
  }
  void add(size_t first, size_t count, const double* hessians) {
    double* values = matrix.valuePtr();
    const size_t kk = static_cast<size_t>(element_size) * element_size;
    const int* at_position = position.data() + first * kk;
    for (size_t i = 0; i < count * kk; ++i)
      if (at_position[i] >= 0) values[at_position[i]] += hessians[i];
  }
};

NewtonMinimizer::NewtonMinimizer() = default;
NewtonMinimizer::~NewtonMinimizer() = default;

NewtonResult NewtonMinimizer::minimize(const ElementObjective& objective, const std::vector<int>& element_unknowns,
                                       int element_size, int free, Eigen::VectorXd& x, int max_iterations,
                                       double gradient_tolerance, double relative_tolerance,
                                       const std::function<bool()>& stop) {
  NewtonResult result;
  if (!system_ || !system_->same(element_unknowns, element_size, free)) {
    // The old system (its factor the largest thing in memory at scale) goes
    // before the new one is built, not after.
    system_.reset();
    system_ = std::make_unique<System>(element_unknowns, element_size, free);
  }
  System& s = *system_;
  Eigen::VectorXd gradient(x.size());
  const HessianSink hessians = [&s](size_t first, size_t count, const double* block) { s.add(first, count, block); };
  // The objective with its gradient and the Hessian assembled.
  const auto evaluate = [&](const Eigen::VectorXd& at) {
    s.clear();
    return objective(at, &gradient, &hessians);
  };
  double value = evaluate(x);
  for (; result.iterations < max_iterations; ++result.iterations) {
    if (!std::isfinite(value) || free == 0 || gradient.head(free).lpNorm<Eigen::Infinity>() < gradient_tolerance) {
      result.converged = std::isfinite(value);
      break;
    }
    if (stop && stop()) {
      result.stopped = true;
      break;
    }
    double* values = s.matrix.valuePtr();
    double mean_diagonal = 0.0;
    for (const int d : s.diagonal) mean_diagonal += std::abs(values[d]);
    mean_diagonal = std::max(mean_diagonal / free, 1e-300);
    const Eigen::VectorXd minus_gradient = -gradient.head(free);
    Eigen::VectorXd step;
    double slope = 0.0, shift = kFirstShift * mean_diagonal, applied = 0.0;
    bool found = false;
    for (int attempt = 0; attempt < kShiftTries && !found; ++attempt, shift *= kShiftGrowth) {
      for (const int d : s.diagonal) values[d] += shift - applied;
      applied = shift;
      try {
        if (!s.analyzed) s.factor.analyze_in_order(s.matrix), s.analyzed = true;
        s.factor.factorize(s.matrix);
        ++result.factorizations;
      } catch (const Error&) {
        s.analyzed = false;  // the factorisation may have changed backend: analyse again
        continue;
      }
      step = s.solve(minus_gradient);
      slope = -minus_gradient.dot(step);
      found = step.allFinite() && slope < 0.0;
    }
    if (!found) {  // no usable curvature: the gradient's direction
      step = minus_gradient / mean_diagonal;
      slope = -minus_gradient.squaredNorm() / mean_diagonal;
    }
    // Newton's model predicts a decrease of -slope / 2 for the full step.
    const bool last = -0.5 * slope <= relative_tolerance * std::abs(value);
    Eigen::VectorXd next = x;
    double next_value = value;
    const auto value_at = [&](double t) {
      next.head(free) = x.head(free) + t * step;
      return objective(next, nullptr, nullptr);
    };
    if (armijo_backtracking(value_at, value, slope, 1.0, next_value) == 0.0) {
      result.converged = true;  // no decrease left at this precision
      break;
    }
    const double decrease = value - next_value;
    x.swap(next);
    value = next_value;
    if (last || decrease <= relative_tolerance * std::abs(value)) {
      result.converged = true;
      ++result.iterations;
      break;
    }
    value = evaluate(x);
  }
  result.value = value;
  return result;
}

}  // namespace polycube
