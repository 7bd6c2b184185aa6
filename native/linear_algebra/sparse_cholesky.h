// The sparse factorisation behind every solve: Eigen's simplicial LDLT for
// small systems, CHOLMOD's supernodal Cholesky (BLAS level 3, one thread: supernodal_factor.cpp)
// for large ones, where it factorises several times faster (see `make bench`),
// from a plugin loaded when the first large system comes (supernodal_factor.h).
//
// The symbolic analysis is done once per sparsity pattern; factorize() may be
// called again with new values (the `current` variant does every iteration).
// Its costliest part, the fill-reducing ordering, can be kept and handed to
// the analysis of the same pattern later (ordering(), analyze(matrix,
// ordering)): the same ordering gives the same factor, bit for bit.
// When the supernodal LLT meets an indefinite matrix (plain cotangent weights
// can be negative) it falls back to LDLT, which handles that.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <utility>
#include <vector>

namespace polycube {

class SparseCholesky {
 public:
  // Systems with at least this many unknowns use CHOLMOD when its plugin loads.
  static constexpr int kSupernodalThreshold = 50'000;
  // Below it, three right-hand sides are solved in one pass on one thread;
  // from it, two and one on two (solve()).
  static constexpr int kSplitSolveFrom = 5'000;

  SparseCholesky();
  ~SparseCholesky();

  // `reused`: the pattern will be factorised many times (the `current`
  // variant). CHOLMOD then chooses its ordering from AMD and METIS, which
  // costs more analysis for faster factorisations (B0 refined to 1.3M
  // triangles: 2.5 s instead of 0.4 s, then 0.85 s instead of 1.1 s per
  // factorisation); otherwise AMD alone.
  void analyze(const Eigen::SparseMatrix<double>& matrix, bool reused = false);
  // The fill-reducing ordering of the last analysis (Eigen's inverse
  // permutation: indices()[k] is the unknown eliminated k-th), whichever
  // backend chose it.
  using Ordering = Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int>;
  const Ordering& ordering() const { return ordering_; }
  // The analysis with `ordering`, from an earlier analysis of the same
  // pattern or made for this one (any permutation gives the right factor;
  // a good one a sparse factor), skipping the ordering's cost: at scale the
  // costliest part of an analysis (B0 refined 16 times: AMD was an eighth of
  // the run). One of the wrong size is ignored (analysed as above).
  void analyze(const Eigen::SparseMatrix<double>& matrix, const Ordering& ordering);
  // The analysis of a matrix already in its elimination order (permuted by
  // an earlier analysis's ordering(), and the same pattern): no ordering,
  // and CHOLMOD's factorisations take the matrix as it is instead of a
  // permuted copy each time (a matrix factorised many times).
  void analyze_in_order(const Eigen::SparseMatrix<double>& matrix);
  // A copy of this analysis, not factorised, when it is CHOLMOD's and
  // nothing has been factorised since (null otherwise, and for Eigen's
  // LDLT): its factorize() gives the factor this one's would, bit for bit,
  // without the analysis (at scale a fifth of a factorisation's time).
  std::unique_ptr<SparseCholesky> copy_analysis() const;
  // Throws Error when the matrix cannot be factorised.
  void factorize(const Eigen::SparseMatrix<double>& matrix);
  // Several right-hand sides are solved in one pass over the factor, each
  // to the bits it would have alone.
  Eigen::MatrixX3d solve(const Eigen::MatrixX3d& rhs) const;
  Eigen::MatrixX2d solve(const Eigen::MatrixX2d& rhs) const;
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) const;

  // Pairs of unknowns held equal: solve(rhs, joins) minimises
  // x^T A x / 2 - b^T x with x_a = x_b for each pair (a, b), A this
  // factor's matrix, without a factorisation of the joined system. With C
  // a row e_a - e_b per join, Y = L^-1 P C^T and S = Y^T Y (k x k for k
  // joins): x = P^T L^-T (z - Y S^-1 Y^T z), z = L^-1 P b, one
  // back-substitution a solve. Y costs only the factor's supernodes on each
  // join's path to the root (supernodal_factor.h).
  struct Joins;
  // Null when this factor cannot hold them: Eigen's LDLT, a Y of more than
  // `max_entries` entries, or joins that would cost more than a quarter of
  // a factorisation (the joined system's own factor then costs little more).
  std::shared_ptr<const Joins> hold_equal(const std::vector<std::pair<int, int>>& joins, long max_entries) const;
  // Equal to rounding: a caller that needs them equal takes one of each pair.
  Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs, const Joins& joins) const;

  // Frees the factor (most of this object's memory) once no more solves are
  // due, or until analyze() again; backend(), factorizations() and
  // ordering() still answer.
  void release();
  bool released() const { return released_backend_ != nullptr; }

  const char* backend() const;
  Eigen::Index rows() const { return rows_; }
  int factorizations() const { return factorizations_; }

 private:
  // Either analysis: with `ordering` when it is not empty.
  void analyze_with(const Eigen::SparseMatrix<double>& matrix, const Ordering& ordering, bool reused);
  struct Backends;
  std::unique_ptr<Backends> backends_;
  int factorizations_ = 0;
  const char* released_backend_ = nullptr;
  Ordering ordering_;
  Eigen::Index rows_ = 0;
};

}  // namespace polycube
