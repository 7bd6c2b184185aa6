// The cotangent Laplacian L of docs/design.md section 2, with +c on the diagonal
// (positive semidefinite for non-negative weights; libigl's cotmatrix is -L).
//
// Its sparsity pattern depends only on the triangles, so it is built once and
// L is refilled in place from new weights: the `current` variant reassembles
// every iteration and the factorisation reuses its symbolic analysis. Every
// vertex has a diagonal entry, isolated ones too, so a regularising term can
// be added to the diagonal.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <vector>

#include "linear_algebra/cotangent_weights.h"

namespace polycube {

using SparseMatrix = Eigen::SparseMatrix<double>;

class Laplacian {
 public:
  Laplacian(int vertex_count, const Triangles& triangles);

  // Refills matrix() from per-triangle weights, then adds `relative_shift`
  // times the mean diagonal to every diagonal entry.
  // Returns the absolute shift added.
  double assemble(const CotangentWeights& weights, double relative_shift = 0.0);

  const SparseMatrix& matrix() const { return matrix_; }

 private:
  SparseMatrix matrix_;
  // For triangle t and corner k (edge opposite k, from v to w): positions in
  // matrix_.valuePtr() of (v,w) and (w,v). Those of (v,v) and (w,w) are
  // diagonal_slots_ of their rows (v is the row of (v,w)): half the memory
  // of keeping all four, which is alive throughout a run (1 MiB on B0).
  std::vector<std::array<int, 2>> slots_;
  std::vector<int> diagonal_slots_;
};

}  // namespace polycube
