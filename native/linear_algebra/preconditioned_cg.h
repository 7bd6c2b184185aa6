// A few conjugate-gradient steps on A X = B (three right-hand sides at once),
// preconditioned by the factorisation of a nearby matrix: the continuous
// fallback's step (docs/design.md section 2.6, stage 5) solves the current
// mesh's Laplacian with the input's factorisation, one back-substitution per
// step instead of a factorisation per iteration.
//
// Inputs: A symmetric positive definite; `preconditioner` factorises a matrix
// of the same size whose inverse is close to A's (the same mesh's Laplacian
// with other weights); `guess` the start (the last solution of a similar
// system: the steps are warm-started across iterations).
// Output: the last iterate, and how far it got. Each column runs its own
// recurrence; a column stops once its residual is below `tolerance` times its
// right-hand side.
#pragma once

#include "linear_algebra/sparse_cholesky.h"

namespace polycube {

struct ConjugateGradient {
  Eigen::MatrixX3d solution;
  int iterations = 0;              // back-substitutions spent
  double relative_residual = 0.0;  // largest over the columns, of the returned solution
};

ConjugateGradient preconditioned_cg(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixX3d& B,
                                    const SparseCholesky& preconditioner, Eigen::MatrixX3d guess,
                                    int max_iterations, double tolerance);

}  // namespace polycube
