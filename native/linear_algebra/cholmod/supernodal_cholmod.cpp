// The plugin behind supernodal_factor.h: Eigen's CHOLMOD wrapper. Built as its
// own shared library so that only a process that factorises a large system
// loads CHOLMOD and the BLAS it needs.
#include <Eigen/CholmodSupport>

#ifdef _OPENMP
#include <omp.h>
#endif

#include <algorithm>
#include <initializer_list>

#include "linear_algebra/supernodal_factor.h"

namespace polycube {
namespace {

// Debian's CHOLMOD (3.0) opens an OpenMP team of a fixed 4 threads for the
// scatter of every large supernode, whatever OMP_NUM_THREADS says: on two
// cores that is thousands of wake-ups per factorisation (armadillo refined
// 4 times: 9 million context switches and a quarter of the run's time in the
// kernel). Its work per team is far below a thread's wake-up, so CHOLMOD's
// regions run on the calling thread: no region opened while this lives is
// active.
class SerialOpenMP {
 public:
#ifdef _OPENMP
  SerialOpenMP() : levels_(omp_get_max_active_levels()) { omp_set_max_active_levels(0); }
  ~SerialOpenMP() { omp_set_max_active_levels(levels_); }

 private:
  int levels_;
#endif
};

// Eigen's wrapper, whose analysis can also start from a known ordering
// (CHOLMOD_GIVEN), or take the matrix in its elimination order already
// (CHOLMOD_NATURAL), and tell the ordering it used.
class Llt : public Eigen::CholmodSupernodalLLT<Eigen::SparseMatrix<double>> {
 public:
  void analyze_given(const Eigen::SparseMatrix<double>& matrix, const Eigen::VectorXi& ordering) {
    analyze_with(matrix, CHOLMOD_GIVEN, const_cast<int*>(ordering.data()));
  }
  void analyze_in_order(const Eigen::SparseMatrix<double>& matrix) {
    // A postorder would leave the factor's ordering no longer natural
    // (cholmod_analyze_p2), and factorisations permuting again.
    const int postorder = cholmod().postorder;
    cholmod().postorder = 0;
    analyze_with(matrix, CHOLMOD_NATURAL, nullptr);
    cholmod().postorder = postorder;
  }
  // Takes a copy of `other`'s symbolic analysis (CHOLMOD's pattern-only
  // factor); false when it has none or has been factorised since.
  bool copy_analysis_from(const Llt& other) {
    cholmod_factor* const symbolic = other.m_cholmodFactor;  // cholmod_copy_factor only reads it
    if (!symbolic || symbolic->xtype != CHOLMOD_PATTERN) return false;
    m_cholmodFactor = cholmod_copy_factor(symbolic, &cholmod());
    m_isInitialized = true;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
    m_info = m_analysisIsOk ? Eigen::Success : Eigen::NumericalIssue;
    return m_analysisIsOk;
  }
  // The numeric factor when it is a supernodal L L^T of doubles (what
  // forward() and forward_joins() read), null otherwise.
  cholmod_factor* supernodal_llt() const {
    cholmod_factor* const l = m_factorizationIsOk ? m_cholmodFactor : nullptr;
    if (!l || !l->is_super || !l->is_ll || l->xtype != CHOLMOD_REAL || l->itype != CHOLMOD_INT) return nullptr;
    return l;
  }
  cholmod_common& common() const { return const_cast<Llt*>(this)->cholmod(); }
  Eigen::VectorXi ordering() const {
    if (!m_cholmodFactor || !m_cholmodFactor->Perm) return {};
    return Eigen::Map<const Eigen::VectorXi>(static_cast<const int*>(m_cholmodFactor->Perm),
                                             static_cast<Eigen::Index>(m_cholmodFactor->n));
  }

 private:
  // The analysis by the one `method`, with `ordering` when it is given.
  void analyze_with(const Eigen::SparseMatrix<double>& matrix, int method, int* ordering) {
    if (m_cholmodFactor) {
      cholmod_free_factor(&m_cholmodFactor, &cholmod());
      m_cholmodFactor = nullptr;
    }
    cholmod_sparse a = Eigen::viewAsCholmod(matrix.selfadjointView<Eigen::Lower>());
    cholmod().nmethods = 1;
    cholmod().method[0].ordering = method;
    m_cholmodFactor = cholmod_analyze_p(&a, ordering, nullptr, 0, &cholmod());
    m_isInitialized = true;
    m_info = m_cholmodFactor ? Eigen::Success : Eigen::InvalidInput;
    m_analysisIsOk = m_cholmodFactor != nullptr;
    m_factorizationIsOk = false;
  }
};

// forward_joins() declines joins that would cost more than this share of
// a factorisation: the joined system's own factor then costs little more.
constexpr double kJoinsShareOfFactorisation = 0.25;

class SupernodalCholmod final : public SupernodalFactor {
 public:
  SupernodalCholmod() { llt_.cholmod().print = 0; }

  bool analyze(const Eigen::SparseMatrix<double>& matrix, bool reused) override {
    if (!reused) {
      llt_.cholmod().nmethods = 1;
      llt_.cholmod().method[0].ordering = CHOLMOD_AMD;
    }
    const SerialOpenMP serial;
    llt_.analyzePattern(matrix);
    return llt_.info() == Eigen::Success;
  }

  bool analyze(const Eigen::SparseMatrix<double>& matrix, const Eigen::VectorXi& ordering) override {
    const SerialOpenMP serial;
    llt_.analyze_given(matrix, ordering);
    return llt_.info() == Eigen::Success;
  }

  bool analyze_in_order(const Eigen::SparseMatrix<double>& matrix) override {
    const SerialOpenMP serial;
    llt_.analyze_in_order(matrix);
    return llt_.info() == Eigen::Success;
  }

  Eigen::VectorXi ordering() const override { return llt_.ordering(); }

  std::unique_ptr<SupernodalFactor> copy_analysis() const override {
    auto copy = std::make_unique<SupernodalCholmod>();
    if (!copy->llt_.copy_analysis_from(llt_)) return nullptr;
    return copy;
  }

  bool factorize(const Eigen::SparseMatrix<double>& matrix) override {
    const SerialOpenMP serial;
    llt_.factorize(matrix);
    return llt_.info() == Eigen::Success;
  }

  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const override {
    const SerialOpenMP serial;
    return llt_.solve(rhs);
  }

  bool forward(Eigen::MatrixXd& columns) const override { return solve_in_place(columns, {CHOLMOD_P, CHOLMOD_L}); }

  bool backward(Eigen::MatrixXd& columns) const override { return solve_in_place(columns, {CHOLMOD_Lt, CHOLMOD_Pt}); }

  bool forward_joins(const std::vector<std::pair<int, int>>& joins, long max_entries, std::vector<int>& rows,
                     Eigen::MatrixXd& y, Eigen::MatrixXd& yty) const override {
    const cholmod_factor* l = llt_.supernodal_llt();
    if (!l) return false;
    const int n = static_cast<int>(l->n), supernodes = static_cast<int>(l->nsuper);
    const int* super = static_cast<const int*>(l->super);  // each supernode's first column
    const int* pi = static_cast<const int*>(l->pi);        // its first row index in `s`
    const int* px = static_cast<const int*>(l->px);        // its first value in `x`, by columns
    const int* s = static_cast<const int*>(l->s);
    const double* x = static_cast<const double*>(l->x);
    const int* perm = static_cast<const int*>(l->Perm);
    std::vector<int> order_of(n), supernode_of(n);
    for (int k = 0; k < n; ++k) order_of[perm ? perm[k] : k] = k;
    for (int sn = 0; sn < supernodes; ++sn)
      for (int c = super[sn]; c < super[sn + 1]; ++c) supernode_of[c] = sn;
    // A supernode's parent holds its first row below its diagonal block.
    auto parent = [&](int sn) {
      const int columns = super[sn + 1] - super[sn];
      return pi[sn + 1] - pi[sn] > columns ? supernode_of[s[pi[sn] + columns]] : -1;
    };
    // (supernode, join) for every supernode on a join's paths to the root:
    // where its column of Y can be nonzero.
    const int k = static_cast<int>(joins.size());
    std::vector<std::pair<int, int>> on_path;
    std::vector<int> last_join(supernodes, -1);
    for (int j = 0; j < k; ++j)
      for (int unknown : {joins[j].first, joins[j].second})
        for (int sn = supernode_of[order_of[unknown]]; sn >= 0 && last_join[sn] != j; sn = parent(sn)) {
          last_join[sn] = j;
          on_path.emplace_back(sn, j);
        }
    std::sort(on_path.begin(), on_path.end());
    // Where each supernode's joins begin in on_path, and its end.
    std::vector<size_t> group;
    for (size_t i = 0; i < on_path.size(); ++i)
      if (i == 0 || on_path[i - 1].first != on_path[i].first) group.push_back(i);
    group.push_back(on_path.size());
    auto supernode = [&](size_t g) { return on_path[group[g]].first; };
    const size_t groups = group.size() - 1;
    std::vector<int> position(n, -1);
    rows.clear();
    for (size_t g = 0; g < groups; ++g)
      for (int c = super[supernode(g)]; c < super[supernode(g) + 1]; ++c) {
        position[c] = static_cast<int>(rows.size());
        rows.push_back(c);
      }
    if (static_cast<long>(rows.size()) * k > max_entries) return false;
    // Declined where it would cost more than kJoinsShareOfFactorisation of
    // factorising the joined system: each supernode's part of Y and Y^T Y
    // on the joins passing it, and S's own factorisation, against the
    // factor's updates (each supernode's rows squared by its columns).
    auto width = [&](int sn) { return static_cast<double>(super[sn + 1] - super[sn]); };
    auto height = [&](int sn) { return static_cast<double>(pi[sn + 1] - pi[sn]); };
    double joins_cost = static_cast<double>(k) * k * k / 3.0, factor_cost = 0.0;
    for (size_t g = 0; g < groups; ++g) {
      const double passing = static_cast<double>(group[g + 1] - group[g]);
      joins_cost += passing * width(supernode(g)) * (height(supernode(g)) + passing);
    }
    for (int sn = 0; sn < supernodes; ++sn) factor_cost += width(sn) * height(sn) * height(sn);
    if (joins_cost > kJoinsShareOfFactorisation * factor_cost) return false;
    y.setZero(static_cast<Eigen::Index>(rows.size()), k);
    yty.setZero(k, k);
    for (int j = 0; j < k; ++j) {
      y(position[order_of[joins[j].first]], j) += 1.0;
      y(position[order_of[joins[j].second]], j) -= 1.0;
    }
    // Supernode by supernode from the leaves, as CHOLMOD's forward solve,
    // on the columns of Y whose paths pass it alone.
    Eigen::MatrixXd block;
    for (size_t g = 0; g < groups; ++g) {
      const int sn = supernode(g), columns = super[sn + 1] - super[sn], rows_below = pi[sn + 1] - pi[sn] - columns;
      const int* row = s + pi[sn];
      const Eigen::Map<const Eigen::MatrixXd, 0, Eigen::OuterStride<>> lower(
          x + px[sn], columns + rows_below, columns, Eigen::OuterStride<>(columns + rows_below));
      const int m = static_cast<int>(group[g + 1] - group[g]);
      auto join = [&](int c) { return on_path[group[g] + c].second; };
      block.resize(columns + rows_below, m);
      for (int c = 0; c < m; ++c)
        for (int r = 0; r < block.rows(); ++r) block(r, c) = y(position[row[r]], join(c));
      lower.topRows(columns).triangularView<Eigen::Lower>().solveInPlace(block.topRows(columns));
      if (rows_below > 0)
        block.bottomRows(rows_below).noalias() -= lower.bottomRows(rows_below) * block.topRows(columns);
      for (int c = 0; c < m; ++c)
        for (int r = 0; r < block.rows(); ++r) y(position[row[r]], join(c)) = block(r, c);
      // These rows of Y are final: their part of Y^T Y.
      const Eigen::MatrixXd product = block.topRows(columns).transpose() * block.topRows(columns);
      for (int a = 0; a < m; ++a)
        for (int b = 0; b < m; ++b) yty(join(a), join(b)) += product(a, b);
    }
    return true;
  }

 private:
  // `columns` through CHOLMOD's solves of `systems`, one after the other.
  bool solve_in_place(Eigen::MatrixXd& columns, std::initializer_list<int> systems) const {
    cholmod_factor* l = llt_.supernodal_llt();
    if (!l || columns.rows() != static_cast<Eigen::Index>(l->n)) return false;
    const SerialOpenMP serial;
    for (int system : systems) {
      cholmod_dense b{};
      b.nrow = static_cast<size_t>(columns.rows());
      b.ncol = static_cast<size_t>(columns.cols());
      b.nzmax = b.nrow * b.ncol;
      b.d = b.nrow;
      b.x = columns.data();
      b.xtype = CHOLMOD_REAL;
      b.dtype = CHOLMOD_DOUBLE;
      cholmod_dense* solved = cholmod_solve(system, l, &b, &llt_.common());
      if (!solved) return false;
      std::copy_n(static_cast<const double*>(solved->x), columns.size(), columns.data());
      cholmod_free_dense(&solved, &llt_.common());
    }
    return true;
  }

  Llt llt_;
};

}  // namespace
}  // namespace polycube

// The one symbol the plugin exports (supernodal_factor.cpp looks it up).
extern "C" __attribute__((visibility("default"))) polycube::SupernodalFactor* polycube_new_supernodal_factor() {
  return new polycube::SupernodalCholmod();
}
