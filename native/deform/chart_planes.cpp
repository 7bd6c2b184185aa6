#include "deform/chart_planes.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <array>
#include <type_traits>
#include <utility>

#include "linear_algebra/run_tasks.h"
#include "linear_algebra/sparse_cholesky.h"

namespace polycube {

// A system whose unknowns each join one or more of its charts' (a few
// collapses): the minimiser of x^T A x / 2 - b^T x over the charts'
// unknowns with the joined ones held equal, C x = 0 (a row e_a - e_b per
// join), is that of the system's own P^T L P. With W = A^-1 C^T and the
// Schur complement S = C W (k x k for k joins): x = y - W S^-1 C y, y =
// A^-1 b, for k back-substitutions once instead of a factorisation.
// At scale W would take a column of the charts' size per join; the charts'
// factor holds them instead, from sparse forward solves
// (SparseCholesky::hold_equal).
struct ChartPlanes::Merged {
  std::vector<int> representative;  // per unknown of the system: one of the charts' unknowns it joins
  std::vector<std::pair<int, int>> joins;
  Eigen::MatrixXd correction;  // W
  Eigen::LDLT<Eigen::MatrixXd> schur;
  std::shared_ptr<const SparseCholesky::Joins> held;  // at scale, instead of W and S

  // From y = A^-1 b (a column per right-hand side) to x.
  template <class Columns>
  void hold_joins(Columns& y) const {
    if (joins.empty() || held) return;
    Eigen::MatrixXd apart(joins.size(), y.cols());
    for (size_t j = 0; j < joins.size(); ++j) apart.row(j) = y.row(joins[j].first) - y.row(joins[j].second);
    y -= correction * schur.solve(apart);
  }
};

namespace {

// Merging beyond this many joins costs more back-substitutions than a
// factorisation saves (B0: a factorisation is about 30 of its
// back-substitutions).
constexpr int kMergedJoinsAtMost = 16;
// At scale a join costs the factor's supernodes on two paths to its root,
// a small part of a back-substitution: B0 refined 64 times collapses 203
// slivers, 112 and 96 joins on charts of 453,634 and 389,266 unknowns,
// whose Y has 8,064 and 6,190 rows: its flattening 5.8 -> 2.8 s, with
// two factorisations fewer, and 650 MiB less at the peak. The joins' Y has
// at most this many entries per unknown of the charts.
constexpr int kHeldJoinsAtMost = 2'048;
constexpr long kHeldEntriesPerUnknown = 32;

}  // namespace

ChartPlanes::ChartPlanes(int vertex_count, const Triangles& triangles, const std::vector<int>& triangle_labels)
    : triangles_(triangles) {
  sets_.fill(UnionFind(vertex_count));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    if (triangle_labels[t] >= 0) collapse(t, triangle_labels[t] / 2);
  charts_only_.fill(true);
}

int ChartPlanes::root(int axis, int v) const { return sets_[axis].root(v); }

std::vector<int> ChartPlanes::current_unknowns(int axis) const {
  std::vector<int> of_root, unknown;
  number_unknowns(axis, sets_[axis].size(), of_root, unknown);
  return unknown;
}

void ChartPlanes::join(int axis, int a, int b) {
  if (sets_[axis].join(a, b)) {
    changed_[axis] = true;
    charts_only_[axis] = false;
  }
}

void ChartPlanes::use_chart_factors(const ChartPlanes& same_charts) {
  chart_orderings_ = same_charts.chart_orderings_;
  std::vector<int> of_root, unknown;
  for (int axis = 0; axis < 3; ++axis) {
    const std::shared_ptr<const ChartFactor>& charts = same_charts.chart_factor_[axis];
    if (!charts || !charts_only_[axis]) continue;
    // A chart factor shared with planes of other labels (share_factors) is not this one's.
    number_unknowns(axis, sets_[axis].size(), of_root, unknown);
    if (unknown != charts->unknown) continue;
    chart_factor_[axis] = charts;
    cholesky_[axis] = charts->cholesky;
    unknown_[axis] = charts->unknown;
    merged_[axis].reset();
    changed_[axis] = false;
  }
}

void ChartPlanes::share_factors(const ChartPlanes& other) {
  std::vector<int> of_root, unknown;
  for (int axis = 0; axis < 3; ++axis) {
    if (!chart_orderings_[axis]) chart_orderings_[axis] = other.chart_orderings_[axis];
    // To merge onto, where this one collapsed what `other` did not.
    if (!chart_factor_[axis]) chart_factor_[axis] = other.chart_factor_[axis];
    if (other.changed_[axis] || !other.cholesky_[axis]) continue;
    const int n = sets_[axis].size();
    if (n != static_cast<int>(other.unknown_[axis].size())) continue;
    number_unknowns(axis, n, of_root, unknown);
    if (unknown != other.unknown_[axis]) continue;
    unknown_[axis] = std::move(unknown);
    cholesky_[axis] = other.cholesky_[axis];
    merged_[axis] = other.merged_[axis];
    changed_[axis] = false;
  }
}

int ChartPlanes::number_unknowns(int axis, int n, std::vector<int>& of_root, std::vector<int>& unknown) const {
  of_root.assign(n, -1);
  unknown.resize(n);
  int m = 0;
  for (int v = 0; v < n; ++v) {
    const int r = root(axis, v);
    if (of_root[r] < 0) of_root[r] = m++;
    unknown[v] = of_root[r];
  }
  return m;
}

void ChartPlanes::release() {
  for (int axis = 0; axis < 3; ++axis) {
    cholesky_[axis].reset();
    chart_factor_[axis].reset();
    merged_[axis].reset();
    changed_[axis] = true;
  }
}

void ChartPlanes::collapse(Eigen::Index t, int axis) {
  join(axis, triangles_(t, 0), triangles_(t, 1));
  join(axis, triangles_(t, 0), triangles_(t, 2));
}

namespace {

// P^T L P: the entries of merged vertices add up, column by column of the
// result, without the triplet list setFromTriplets would need (1 MiB on B0,
// at the run's peak memory). The same sums in the same order as that list
// (L's columns, then its rows, ascending), so the same matrix bit for bit:
// each sum starts from its first term, not from 0 (0.0 + -0.0 is +0.0).
Eigen::SparseMatrix<double> reduced_matrix(const Eigen::SparseMatrix<double>& laplacian,
                                           const std::vector<int>& unknown, int unknowns) {
  const int n = static_cast<int>(laplacian.rows());
  // L's columns grouped by their unknown, ascending within a group.
  std::vector<int> first(unknowns + 1, 0), columns(n);
  for (int v = 0; v < n; ++v) ++first[unknown[v] + 1];
  for (int j = 0; j < unknowns; ++j) first[j + 1] += first[j];
  {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int v = 0; v < n; ++v) columns[next[unknown[v]]++] = v;
  }
  std::vector<double> sum(unknowns);
  std::vector<char> seen(unknowns, 0);
  std::vector<int> rows;
  // Column j's rows, ascending, with their sums in `sum`.
  auto gather = [&](int j) {
    rows.clear();
    for (int k = first[j]; k < first[j + 1]; ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, columns[k]); it; ++it) {
        const int i = unknown[it.row()];
        if (seen[i]) {
          sum[i] += it.value();
        } else {
          seen[i] = 1;
          sum[i] = it.value();
          rows.push_back(i);
        }
      }
    std::sort(rows.begin(), rows.end());
    for (int i : rows) seen[i] = 0;
  };
  // Twice: the sizes first, so the matrix is allocated once, at its size.
  Eigen::SparseMatrix<double> reduced(unknowns, unknowns);
  int* outer = reduced.outerIndexPtr();
  outer[0] = 0;
  for (int j = 0; j < unknowns; ++j) {
    gather(j);
    outer[j + 1] = outer[j] + static_cast<int>(rows.size());
  }
  reduced.resizeNonZeros(outer[unknowns]);
  for (int j = 0; j < unknowns; ++j) {
    gather(j);
    int e = outer[j];
    for (int i : rows) {
      reduced.innerIndexPtr()[e] = i;
      reduced.valuePtr()[e++] = sum[i];
    }
  }
  return reduced;
}

// An ordering for a system each of whose unknowns joins one or more of an
// ordered system's (`ordered_unknown` and `unknown`: each vertex's unknown in
// either): each unknown eliminated where the last of those it joins was.
// Collapses join a few unknowns and leave the graph nearly as it was, and
// its ordering nearly as good, without an analysis's costliest part. Empty
// when the systems are not so related.
SparseCholesky::Ordering joined_ordering(const SparseCholesky::Ordering& ordered,
                                         const std::vector<int>& ordered_unknown, const std::vector<int>& unknown,
                                         int unknowns) {
  const Eigen::Index m = ordered.size();
  if (m == 0 || ordered_unknown.size() != unknown.size()) return {};
  std::vector<int> into(m, -1);
  for (size_t v = 0; v < unknown.size(); ++v) {
    int& joined = into[ordered_unknown[v]];
    if (joined >= 0 && joined != unknown[v]) return {};  // split, not joined
    joined = unknown[v];
  }
  std::vector<Eigen::Index> last(unknowns, -1);
  for (Eigen::Index k = 0; k < m; ++k) last[into[ordered.indices()[k]]] = k;
  SparseCholesky::Ordering joined(unknowns);
  int next = 0;
  for (Eigen::Index k = 0; k < m; ++k) {
    const int u = into[ordered.indices()[k]];
    if (last[u] == k) joined.indices()[next++] = u;
  }
  return joined;
}

}  // namespace

ChartPlanes::NumberedAxes ChartPlanes::numbered_axes(int n, const std::array<bool, 3>& wanted) const {
  NumberedAxes numbered;
  std::vector<int> of_root;
  for (int axis = 0; axis < 3; ++axis) {
    if (!wanted[axis]) continue;
    // Serial: finding roots compresses paths.
    numbered.unknowns[axis] = number_unknowns(axis, n, of_root, numbered.unknown[axis]);
    numbered.axes.push_back(axis);
  }
  const auto& unknowns = numbered.unknowns;
  std::stable_sort(numbered.axes.begin(), numbered.axes.end(),
                   [&](int a, int b) { return unknowns[a] > unknowns[b]; });
  return numbered;
}

void ChartPlanes::order(const Eigen::SparseMatrix<double>& laplacian) {
  std::array<bool, 3> wanted{};
  for (int axis = 0; axis < 3; ++axis) wanted[axis] = !chart_orderings_[axis] && charts_only_[axis];
  // Inside another task, one after the other.
  NumberedAxes numbered = numbered_axes(static_cast<int>(laplacian.rows()), wanted);
  const std::vector<int>& axes = numbered.axes;
  run_tasks(static_cast<int>(axes.size()), [&](int i) {
    const int axis = axes[i];
    SparseCholesky analysis;
    analysis.analyze(reduced_matrix(laplacian, numbered.unknown[axis], numbered.unknowns[axis]));
    chart_orderings_[axis] = std::make_shared<const ChartOrdering>(
        ChartOrdering{analysis.ordering(), std::move(numbered.unknown[axis]), analysis.copy_analysis()});
  });
}

void ChartPlanes::use_orderings(const ChartPlanes& ordered) {
  for (int axis = 0; axis < 3; ++axis)
    if (!chart_orderings_[axis]) chart_orderings_[axis] = ordered.chart_orderings_[axis];
}

void ChartPlanes::factorize(const Eigen::SparseMatrix<double>& laplacian) { factorize(laplacian, 3); }

void ChartPlanes::factorize(const Eigen::SparseMatrix<double>& laplacian, int at_most, bool merge) {
  // The axes' systems are independent: one a thread (numbered_axes).
  NumberedAxes numbered = numbered_axes(static_cast<int>(laplacian.rows()), changed_);
  std::vector<int>& axes = numbered.axes;
  const std::array<int, 3>& unknowns = numbered.unknowns;
  if (static_cast<int>(axes.size()) > at_most) axes.resize(at_most);
  for (int axis : axes) {
    changed_[axis] = false;
    unknown_[axis] = std::move(numbered.unknown[axis]);
    cholesky_[axis].reset();  // before the new factor: never two of one axis in memory
    merged_[axis].reset();
  }
  std::array<char, 3> factorized{};
  run_tasks(static_cast<int>(axes.size()),
            [&](int i) { factorized[i] = factorize_axis(laplacian, axes[i], unknowns[axes[i]], merge); });
  for (char f : factorized) factorizations_ += f;
}

std::shared_ptr<const ChartPlanes::Merged> ChartPlanes::merged_onto_charts(int axis, int m) const {
  const ChartFactor* charts = chart_factor_[axis].get();
  if (!charts) return nullptr;
  const SparseCholesky& factor = *charts->cholesky;
  const int chart_unknowns = static_cast<int>(factor.rows());
  const std::vector<int>& unknown = unknown_[axis];
  const int joins = chart_unknowns - m;
  const bool at_scale = chart_unknowns >= SparseCholesky::kSupernodalThreshold;
  if (joins < 0 || joins > (at_scale ? kHeldJoinsAtMost : kMergedJoinsAtMost) ||
      charts->unknown.size() != unknown.size())
    return nullptr;
  // Each of the charts' unknowns into the one of this system it joins.
  std::vector<int> into(chart_unknowns, -1);
  for (size_t v = 0; v < unknown.size(); ++v) {
    int& joined = into[charts->unknown[v]];
    if (joined >= 0 && joined != unknown[v]) return nullptr;  // split, not joined
    joined = unknown[v];
  }
  auto merged = std::make_shared<Merged>();
  merged->representative.assign(m, -1);
  for (int c = 0; c < chart_unknowns; ++c) {
    if (into[c] < 0) return nullptr;
    int& first = merged->representative[into[c]];
    if (first < 0)
      first = c;
    else
      merged->joins.emplace_back(first, c);
  }
  if (static_cast<int>(merged->joins.size()) != joins) return nullptr;
  if (at_scale) {
    merged->held = factor.hold_equal(merged->joins, kHeldEntriesPerUnknown * chart_unknowns);
    return merged->held ? merged : nullptr;
  }
  merged->correction.resize(chart_unknowns, joins);
  Eigen::VectorXd c = Eigen::VectorXd::Zero(chart_unknowns);
  for (int j = 0; j < joins; ++j) {
    const auto [a, b] = merged->joins[j];
    c[a] = 1.0, c[b] = -1.0;
    merged->correction.col(j) = factor.solve(c);
    c[a] = c[b] = 0.0;
  }
  Eigen::MatrixXd schur(joins, joins);
  for (int j = 0; j < joins; ++j)
    schur.row(j) = merged->correction.row(merged->joins[j].first) - merged->correction.row(merged->joins[j].second);
  if (joins > 0) merged->schur.compute(schur);
  if (joins > 0 && merged->schur.info() != Eigen::Success) return nullptr;
  return merged;
}

bool ChartPlanes::factorize_axis(const Eigen::SparseMatrix<double>& laplacian, int axis, int m, bool merge) {
  if (!charts_only_[axis]) {
    if (std::shared_ptr<const Merged> merged = merge ? merged_onto_charts(axis, m) : nullptr) {
      cholesky_[axis] = chart_factor_[axis]->cholesky;
      merged_[axis] = std::move(merged);
      return false;
    }
  }
  chart_factor_[axis].reset();  // before the new factor: never two of one axis in memory
  const std::vector<int>& unknown = unknown_[axis];
  const Eigen::SparseMatrix<double> reduced = reduced_matrix(laplacian, unknown, m);
  // The charts' own ordering when known; at scale, one joined from it for
  // a system with collapses (where an analysis costs most); otherwise
  // computed. Below that, a system with collapses is analysed afresh as
  // it always was: another ordering rounds its factor otherwise, and the
  // runs' decisions follow figures near their bounds (the anchor's last
  // resort ended with 15% of its area collapsed instead of 0.03%). The
  // charts' own system, analysed before at scale, is not analysed again.
  const ChartOrdering* charts = chart_orderings_[axis].get();
  const bool joined =
      charts && (charts_only_[axis] ? charts->unknown == unknown : m >= SparseCholesky::kSupernodalThreshold);
  std::shared_ptr<SparseCholesky> cholesky;
  if (joined && charts_only_[axis] && charts->analysis) cholesky = charts->analysis->copy_analysis();
  if (!cholesky) {
    cholesky = std::make_shared<SparseCholesky>();
    cholesky->analyze(
        reduced, joined ? joined_ordering(charts->ordering, charts->unknown, unknown, m) : SparseCholesky::Ordering());
    if (charts_only_[axis] && !joined)
      chart_orderings_[axis] = std::make_shared<const ChartOrdering>(
          ChartOrdering{cholesky->ordering(), unknown, cholesky->copy_analysis()});
  }
  cholesky->factorize(reduced);
  cholesky_[axis] = std::move(cholesky);
  if (charts_only_[axis])
    chart_factor_[axis] = std::make_shared<const ChartFactor>(ChartFactor{cholesky_[axis], unknown});
  return true;
}

template <int K>
std::array<Vertices, K> ChartPlanes::solve_together(const std::array<const Eigen::MatrixX3d*, K>& rhs,
                                                    const std::function<void()>& beside) const {
  // A vector for one solve: SparseCholesky solves it as a vector.
  using Columns = std::conditional_t<K == 1, Eigen::VectorXd, Eigen::Matrix<double, Eigen::Dynamic, K>>;
  solves_ += K;
  const Eigen::Index n = rhs[0]->rows();
  std::array<Vertices, K> x;
  for (Vertices& solution : x) solution.resize(n, 3);
  // Independent back-substitutions, each axis's on a thread of its own.
  run_tasks(beside ? 4 : 3, [&](int axis) {
    if (axis == 3) return beside();
    const Merged* merged = merged_[axis].get();
    const std::vector<int>& unknown = merged ? chart_factor_[axis]->unknown : unknown_[axis];
    Columns b = Columns::Zero(cholesky_[axis]->rows(), K);
    for (Eigen::Index v = 0; v < n; ++v)
      for (int k = 0; k < K; ++k) b(unknown[v], k) += (*rhs[k])(v, axis);
    Columns y;
    if (merged && merged->held)
      y = cholesky_[axis]->solve(Eigen::MatrixXd(b), *merged->held);
    else
      y = cholesky_[axis]->solve(b);
    if (!merged) {
      for (Eigen::Index v = 0; v < n; ++v)
        for (int k = 0; k < K; ++k) x[k](v, axis) = y(unknown[v], k);
      return;
    }
    // Joined vertices take one value: collapsed exactly, not to rounding.
    merged->hold_joins(y);
    const std::vector<int>& joined = unknown_[axis];
    for (Eigen::Index v = 0; v < n; ++v)
      for (int k = 0; k < K; ++k) x[k](v, axis) = y(merged->representative[joined[v]], k);
  });
  return x;
}

Vertices ChartPlanes::solve(const Eigen::MatrixX3d& rhs) const { return std::move(solve_together<1>({&rhs})[0]); }

std::array<Vertices, 2> ChartPlanes::solve(const Eigen::MatrixX3d& first, const Eigen::MatrixX3d& second,
                                           const std::function<void()>& beside) const {
  return solve_together<2>({&first, &second}, beside);
}

bool ChartPlanes::solve_near(const Eigen::SparseMatrix<double>& laplacian, const Eigen::MatrixX3d& rhs,
                             const std::vector<char>& region, Vertices& positions) const {
  const int n = static_cast<int>(positions.rows());
  const double scale = std::max(1.0, positions.cwiseAbs().maxCoeff());
  Vertices result = positions;
  // The axes are independent (each its own sets, its own column of
  // `result`): each on a thread of its own.
  std::array<char, 3> placed = {1, 1, 1};
  run_tasks(3, [&](int axis) {
    std::vector<int> unknown(n, -1), of_root(n, -1);
    std::vector<double> lo(n), hi(n);
    std::vector<char> held(n, 0);
    // A set with a vertex outside the region is held at that vertex's value;
    // all of its outside vertices must agree on it.
    for (int v = 0; v < n; ++v) {
      if (region[v]) continue;
      const int r = root(axis, v);
      if (!held[r]) lo[r] = hi[r] = positions(v, axis);
      held[r] = 1;
      lo[r] = std::min(lo[r], positions(v, axis));
      hi[r] = std::max(hi[r], positions(v, axis));
    }
    int m = 0;
    for (int v = 0; v < n; ++v) {
      const int r = root(axis, v);
      if (held[r]) {
        if (hi[r] - lo[r] > 1e-12 * scale) {
          placed[axis] = 0;
          return;
        }
        result(v, axis) = lo[r];
      } else {
        if (of_root[r] < 0) of_root[r] = m++;
        unknown[v] = of_root[r];
      }
    }
    if (m == 0) return;
    Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
    std::vector<Eigen::Triplet<double>> entries;
    for (int column = 0; column < laplacian.outerSize(); ++column)
      for (Eigen::SparseMatrix<double>::InnerIterator it(laplacian, column); it; ++it) {
        const int row = unknown[it.row()];
        if (row < 0) continue;
        if (unknown[column] >= 0)
          entries.emplace_back(row, unknown[column], it.value());
        else
          b[row] -= it.value() * result(column, axis);
      }
    for (int v = 0; v < n; ++v)
      if (unknown[v] >= 0) b[unknown[v]] += rhs(v, axis);
    Eigen::SparseMatrix<double> reduced(m, m);
    reduced.setFromTriplets(entries.begin(), entries.end());
    SparseCholesky local;
    local.analyze(reduced);
    local.factorize(reduced);
    const Eigen::VectorXd y = local.solve(b);
    for (int v = 0; v < n; ++v)
      if (unknown[v] >= 0) result(v, axis) = y[unknown[v]];
  });
  if (!placed[0] || !placed[1] || !placed[2]) return false;
  positions = std::move(result);
  return true;
}

}  // namespace polycube
