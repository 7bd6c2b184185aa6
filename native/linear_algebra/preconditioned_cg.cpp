#include "linear_algebra/preconditioned_cg.h"

#include <Eigen/SparseCore>

namespace polycube {

ConjugateGradient preconditioned_cg(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixX3d& B,
                                    const SparseCholesky& preconditioner, Eigen::MatrixX3d guess,
                                    int max_iterations, double tolerance) {
  ConjugateGradient cg;
  cg.solution = std::move(guess);
  Eigen::MatrixX3d residual = B - A * cg.solution;
  const Eigen::Array3d target = tolerance * B.colwise().norm().array();
  Eigen::Array3d norms = residual.colwise().norm().array();
  Eigen::MatrixX3d direction, z;
  Eigen::Array3d rz = Eigen::Array3d::Zero();
  for (; cg.iterations < max_iterations && (norms > target).any(); ++cg.iterations) {
    z = preconditioner.solve(residual);
    const Eigen::Array3d rz_new = (residual.array() * z.array()).colwise().sum();
    if (cg.iterations == 0) {
      direction = z;
    } else {
      const Eigen::Array3d beta = (rz > 0.0).select(rz_new / rz, 0.0);
      direction = z + direction * beta.matrix().asDiagonal();
    }
    rz = rz_new;
    const Eigen::MatrixX3d Ad = A * direction;
    const Eigen::Array3d curvature = (direction.array() * Ad.array()).colwise().sum();
    // A converged column (or one whose direction vanished) stands still.
    const Eigen::Array3d alpha = (norms > target && curvature > 0.0).select(rz / curvature, 0.0);
    cg.solution += direction * alpha.matrix().asDiagonal();
    residual -= Ad * alpha.matrix().asDiagonal();
    norms = residual.colwise().norm().array();
  }
  const Eigen::Array3d scale = B.colwise().norm().array();
  cg.relative_residual = (scale > 0.0).select(norms / scale, norms).maxCoeff();
  return cg;
}

}  // namespace polycube
