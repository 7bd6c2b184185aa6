#include "linear_algebra/sparse_cholesky.h"

#include <Eigen/Cholesky>
#include <Eigen/SparseCholesky>

#include "linear_algebra/run_tasks.h"
#include "linear_algebra/supernodal_factor.h"
#include "mesh/mesh.h"

namespace polycube {

namespace {

using Matrix = Eigen::SparseMatrix<double>;

// Eigen's LDLT, whose analysis can also start from a known ordering: the
// steps of its own analyzePattern (SimplicialCholesky.h) with the AMD call
// replaced.
class Simplicial : public Eigen::SimplicialLDLT<Matrix, Eigen::Lower, Eigen::AMDOrdering<int>> {
 public:
  // Eigen's analyzePattern, the same ordering for a fifth less: its
  // AMDOrdering first adds the transpose to the matrix, whose full symmetric
  // form already has that pattern, sorted the same (B0's analyses 10% fewer
  // instructions).
  void analyze_amd(const Matrix& a) {
    if (a.rows() == 0) return analyzePattern(a);
    {
      Matrix full;
      full = a.selfadjointView<Eigen::Lower>();
      Eigen::internal::minimum_degree_ordering(full, m_Pinv);
    }
    m_P = m_Pinv.inverse();
    CholMatrixType ap(a.rows(), a.cols());
    ap.selfadjointView<Eigen::Upper>() = a.selfadjointView<Eigen::Lower>().twistedBy(m_P);
    analyzePattern_preordered(ap, true);
  }
  void analyze_ordered(const Matrix& a, const SparseCholesky::Ordering& ordering) {
    m_Pinv = ordering;
    m_P = ordering.inverse();
    CholMatrixType ap(a.rows(), a.cols());
    ap.selfadjointView<Eigen::Upper>() = a.selfadjointView<Eigen::Lower>().twistedBy(m_P);
    analyzePattern_preordered(ap, true);
  }

  // Eigen's solve (SimplicialCholeskyBase::_solve_impl and the sparse
  // triangular solves it calls, SparseCore/TriangularSolver.h) of every
  // column of `b` in one pass over the factor instead of one pass per
  // column: each column takes the same operations in the same order, so
  // the same bits (a test compares them), while the factor, larger than
  // the cache, is read once. `Columns` is the number of columns.
  template <int Columns>
  Eigen::Matrix<double, Eigen::Dynamic, Columns> solve_columns(
      const Eigen::Matrix<double, Eigen::Dynamic, Columns>& b) const {
    using Rows = Eigen::Matrix<double, Eigen::Dynamic, Columns, Columns == 1 ? Eigen::ColMajor : Eigen::RowMajor>;
    const Eigen::Index n = m_matrix.rows();
    Rows x;
    if (m_P.size() > 0)
      x = m_P * b;
    else
      x = b;
    // L y = x, L unit lower and stored by columns (its strict lower part).
    for (Eigen::Index i = 0; i < n; ++i) {
      bool nonzero[Columns];
      bool any = false;
      for (int c = 0; c < Columns; ++c) any |= nonzero[c] = x(i, c) != 0.0;  // Eigen skips a zero column entry
      if (!any) continue;
      CholMatrixType::InnerIterator it(m_matrix, i);
      while (it && it.index() <= i) ++it;
      for (; it; ++it)
        for (int c = 0; c < Columns; ++c)
          if (nonzero[c]) x(it.index(), c) -= x(i, c) * it.value();
    }
    // D^-1, as Eigen's diagonal inverse times the columns.
    for (Eigen::Index i = 0; i < m_diag.size(); ++i) {
      const double inverse = 1.0 / m_diag[i];
      for (int c = 0; c < Columns; ++c) x(i, c) = inverse * x(i, c);
    }
    // L^T z = y, row by row from the last.
    for (Eigen::Index i = n - 1; i >= 0; --i) {
      double sum[Columns];
      for (int c = 0; c < Columns; ++c) sum[c] = x(i, c);
      CholMatrixType::InnerIterator it(m_matrix, i);
      while (it && it.index() <= i) ++it;
      for (; it; ++it)
        for (int c = 0; c < Columns; ++c) sum[c] -= it.value() * x(it.index(), c);
      for (int c = 0; c < Columns; ++c) x(i, c) = sum[c];
    }
    if (m_P.size() > 0) return m_Pinv * x;
    return x;
  }
};

}  // namespace

struct SparseCholesky::Backends {
  std::unique_ptr<Simplicial> simplicial;
  std::unique_ptr<SupernodalFactor> supernodal;  // null without the plugin (supernodal_factor.h)
};

SparseCholesky::SparseCholesky() : backends_(std::make_unique<Backends>()) {}
SparseCholesky::~SparseCholesky() = default;

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& matrix, bool reused) {
  analyze_with(matrix, Ordering(), reused);
}

void SparseCholesky::analyze(const Eigen::SparseMatrix<double>& matrix, const Ordering& ordering) {
  analyze_with(matrix, ordering.size() == matrix.rows() ? ordering : Ordering(), false);
}

void SparseCholesky::analyze_in_order(const Eigen::SparseMatrix<double>& matrix) {
  rows_ = matrix.rows();
  released_backend_ = nullptr;
  ordering_.setIdentity(matrix.rows());
  backends_ = std::make_unique<Backends>();
  if (matrix.rows() >= kSupernodalThreshold) {
    std::unique_ptr<SupernodalFactor>& supernodal = backends_->supernodal;
    supernodal = make_supernodal_factor();
    if (supernodal && supernodal->analyze_in_order(matrix)) return;
    supernodal.reset();
  }
  backends_->simplicial = std::make_unique<Simplicial>();
  backends_->simplicial->analyze_ordered(matrix, ordering_);
}

void SparseCholesky::analyze_with(const Eigen::SparseMatrix<double>& matrix, const Ordering& ordering, bool reused) {
  rows_ = matrix.rows();
  released_backend_ = nullptr;
  ordering_ = ordering;
  backends_ = std::make_unique<Backends>();
  const bool given = ordering.size() > 0;
  if (matrix.rows() >= kSupernodalThreshold) {
    std::unique_ptr<SupernodalFactor>& supernodal = backends_->supernodal;
    supernodal = make_supernodal_factor();
    if (supernodal && (given ? supernodal->analyze(matrix, ordering.indices()) : supernodal->analyze(matrix, reused))) {
      ordering_.indices() = supernodal->ordering();
      return;
    }
    supernodal.reset();
  }
  backends_->simplicial = std::make_unique<Simplicial>();
  if (given) {
    backends_->simplicial->analyze_ordered(matrix, ordering_);
  } else {
    backends_->simplicial->analyze_amd(matrix);
    ordering_ = backends_->simplicial->permutationPinv();
  }
}

std::unique_ptr<SparseCholesky> SparseCholesky::copy_analysis() const {
  if (!backends_->supernodal) return nullptr;
  std::unique_ptr<SupernodalFactor> analysis = backends_->supernodal->copy_analysis();
  if (!analysis) return nullptr;
  auto copy = std::make_unique<SparseCholesky>();
  copy->rows_ = rows_;
  copy->ordering_ = ordering_;
  copy->backends_->supernodal = std::move(analysis);
  return copy;
}

void SparseCholesky::factorize(const Eigen::SparseMatrix<double>& matrix) {
  ++factorizations_;
  if (backends_->supernodal) {
    if (backends_->supernodal->factorize(matrix)) return;
    backends_->supernodal.reset();  // not positive definite: LDLT from now on
    backends_->simplicial = std::make_unique<Simplicial>();
    backends_->simplicial->analyze_ordered(matrix, ordering_);
  }
  backends_->simplicial->factorize(matrix);
  if (backends_->simplicial->info() != Eigen::Success)
    throw Error("the sparse factorisation of the Laplacian failed (the mesh may be badly degenerate)");
}

Eigen::MatrixX3d SparseCholesky::solve(const Eigen::MatrixX3d& rhs) const {
  if (backends_->supernodal) return backends_->supernodal->solve(rhs);
  const Simplicial& factor = *backends_->simplicial;
  if (rows_ < kSplitSolveFrom) return factor.solve_columns<3>(rhs);
  // Two columns in one pass and the third beside it on another thread:
  // each column the bits it has alone, two passes over the factor at once
  // instead of one three times as wide (B0's input: 1.2 -> 0.8 ms).
  Eigen::MatrixX3d x(rhs.rows(), 3);
  run_tasks(2, [&](int i) {
    if (i == 0)
      x.leftCols<2>() = factor.solve_columns<2>(rhs.leftCols<2>());
    else
      x.col(2) = factor.solve(Eigen::VectorXd(rhs.col(2)));
  });
  return x;
}

Eigen::MatrixX2d SparseCholesky::solve(const Eigen::MatrixX2d& rhs) const {
  if (backends_->supernodal) return backends_->supernodal->solve(rhs);
  return backends_->simplicial->solve_columns<2>(rhs);
}

Eigen::VectorXd SparseCholesky::solve(const Eigen::VectorXd& rhs) const {
  if (backends_->supernodal) return backends_->supernodal->solve(rhs);
  return backends_->simplicial->solve(rhs);
}

struct SparseCholesky::Joins {
  std::vector<int> rows;  // of L^-1 P, where Y has its nonzeros
  Eigen::MatrixXd y;      // those rows of Y
  Eigen::LDLT<Eigen::MatrixXd> schur;
};

std::shared_ptr<const SparseCholesky::Joins> SparseCholesky::hold_equal(const std::vector<std::pair<int, int>>& joins,
                                                                        long max_entries) const {
  if (!backends_->supernodal) return nullptr;
  auto held = std::make_shared<Joins>();
  Eigen::MatrixXd yty;
  if (!backends_->supernodal->forward_joins(joins, max_entries, held->rows, held->y, yty)) return nullptr;
  held->schur.compute(yty);
  if (held->schur.info() != Eigen::Success || !(held->schur.vectorD().minCoeff() > 0.0)) return nullptr;
  return held;
}

Eigen::MatrixXd SparseCholesky::solve(const Eigen::MatrixXd& rhs, const Joins& joins) const {
  Eigen::MatrixXd z = rhs;
  if (!backends_->supernodal || !backends_->supernodal->forward(z)) throw Error("a joined solve without its factor");
  const auto rows = static_cast<Eigen::Index>(joins.rows.size());
  Eigen::MatrixXd on_rows(rows, z.cols());
  for (Eigen::Index i = 0; i < rows; ++i) on_rows.row(i) = z.row(joins.rows[i]);
  on_rows = joins.y * joins.schur.solve(joins.y.transpose() * on_rows);
  for (Eigen::Index i = 0; i < rows; ++i) z.row(joins.rows[i]) -= on_rows.row(i);
  if (!backends_->supernodal->backward(z)) throw Error("a joined solve without its factor");
  return z;
}

void SparseCholesky::release() {
  released_backend_ = backend();
  backends_ = std::make_unique<Backends>();
}

const char* SparseCholesky::backend() const {
  if (released_backend_) return released_backend_;
  if (backends_->supernodal) return "cholmod-supernodal";
  return "eigen-simplicial";
}

}  // namespace polycube
