// CHOLMOD's supernodal Cholesky behind a small interface, loaded at run time
// from a plugin beside the program or module (polycube_cholmod.so, built from
// cholmod/supernodal_cholmod.cpp) the first time a system is large enough to
// use it. CHOLMOD brings OpenBLAS, LAPACK, METIS and gfortran with it: about
// 5 MiB and 20 ms at start-up that meshes below SparseCholesky's threshold
// (most of what users deform) never use.
//
// Without the plugin (a build without CHOLMOD, or a copy of the program
// without it) make_supernodal_factor() returns null and SparseCholesky
// factorises with Eigen's simplicial LDLT, as a build without CHOLMOD does.
#pragma once

#include <Eigen/SparseCore>
#include <memory>
#include <utility>
#include <vector>

namespace polycube {

class SupernodalFactor {
 public:
  virtual ~SupernodalFactor() = default;
  // `reused`: choose the ordering from AMD and METIS (more analysis, faster
  // factorisations); otherwise AMD alone. False when the analysis failed.
  virtual bool analyze(const Eigen::SparseMatrix<double>& matrix, bool reused) = 0;
  // The analysis with a known fill-reducing ordering (`ordering[k]`: the
  // unknown eliminated k-th), skipping the costliest part of it.
  virtual bool analyze(const Eigen::SparseMatrix<double>& matrix, const Eigen::VectorXi& ordering) = 0;
  // The analysis of a matrix already in its elimination order: CHOLMOD's
  // natural ordering, not postordered, so factorize() takes the matrix as
  // it is, without a permuted copy.
  virtual bool analyze_in_order(const Eigen::SparseMatrix<double>& matrix) = 0;
  // The ordering the last analysis used, in the same convention (empty
  // before one).
  virtual Eigen::VectorXi ordering() const = 0;
  // A new factor holding a copy of this analysis, before any factorize()
  // (null after one, or without an analysis): its factorisation is this
  // one's would-be factor bit for bit, without analysing again.
  virtual std::unique_ptr<SupernodalFactor> copy_analysis() const = 0;
  // False when the matrix is not positive definite (silently: CHOLMOD's own
  // warning would go to stdout, where the program writes its report).
  virtual bool factorize(const Eigen::SparseMatrix<double>& matrix) = 0;
  // Every column of `rhs` in one pass over the factor.
  virtual Eigen::MatrixXd solve(const Eigen::MatrixXd& rhs) const = 0;
  // The two halves of solve(), A^-1 = P^T L^-T L^-1 P: `columns` into
  // L^-1 P columns, and back from there into P^T L^-T columns. False
  // (`columns` left) when the factor is not CHOLMOD's supernodal L L^T.
  virtual bool forward(Eigen::MatrixXd& columns) const = 0;
  virtual bool backward(Eigen::MatrixXd& columns) const = 0;
  // Y = L^-1 P C^T for the columns e_a - e_b of the pairs in `joins`, on
  // the rows of L^-1 P where any of them can be nonzero (`rows`, in L's
  // order; Y is rows.size() x joins.size()), and Y^T Y, from the factor's
  // supernodes on the paths from a and b to the root alone: a few of a
  // solve's operations per join where each has only two nonzeros. False
  // when the factor is not CHOLMOD's L L^T, Y would have more than
  // `max_entries` entries, or the joins would cost more than a quarter of
  // a factorisation.
  virtual bool forward_joins(const std::vector<std::pair<int, int>>& joins, long max_entries, std::vector<int>& rows,
                             Eigen::MatrixXd& y, Eigen::MatrixXd& yty) const = 0;
};

// A new factor from the plugin, or null when it cannot be loaded. The plugin
// is loaded once, on the first call, and stays loaded.
std::unique_ptr<SupernodalFactor> make_supernodal_factor();

// Whether the plugin loads (loading it if it has not been yet).
bool supernodal_available();

}  // namespace polycube
