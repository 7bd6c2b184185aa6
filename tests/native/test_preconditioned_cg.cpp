#include <gtest/gtest.h>

#include "linear_algebra/laplacian.h"
#include "linear_algebra/preconditioned_cg.h"
#include "mesh/triangulate.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

// The clamped, shifted Laplacian of `positions` on the sphere's triangles:
// the continuous fallback's system (positions = the current mesh) and its
// preconditioner (positions = the input).
SparseMatrix laplacian_of(const Vertices& positions, const Triangles& triangles) {
  Laplacian laplacian(static_cast<int>(positions.rows()), triangles);
  laplacian.assemble(cotangent_weights(positions, triangles).cwiseMax(0.0), 1e-8);
  return laplacian.matrix();
}

// The largest over the three columns, as ConjugateGradient reports it.
double residual(const SparseMatrix& a, const Eigen::MatrixX3d& x, const Eigen::MatrixX3d& b) {
  return ((b - a * x).colwise().norm().array() / b.colwise().norm().array()).maxCoeff();
}

// The input: a sphere; the current mesh: the same squeezed to a thin
// ellipsoid, whose weights differ a lot from the input's.
struct SqueezedSphere {
  SparseMatrix input, current;
  SparseCholesky input_factorization;
  Eigen::MatrixX3d rhs;

  SqueezedSphere() {
    const PolygonMesh mesh = test_meshes::uv_sphere(48, 24);
    const Triangles triangles = triangulate(mesh.vertices, mesh.faces).triangles;
    Vertices squeezed = mesh.vertices;
    squeezed.col(2) *= 0.05;
    input = laplacian_of(mesh.vertices, triangles);
    current = laplacian_of(squeezed, triangles);
    input_factorization.analyze(input);
    input_factorization.factorize(input);
    // Solvable as the deformation's systems are: the solution is a shape.
    std::srand(3);
    rhs = current * (Eigen::MatrixX3d(mesh.vertices) + 0.1 * Eigen::MatrixX3d::Random(mesh.vertices.rows(), 3));
  }
};

TEST(PreconditionedCg, ExactPreconditionerSolvesInOneStep) {
  const SqueezedSphere s;
  const ConjugateGradient cg =
      preconditioned_cg(s.input, s.rhs, s.input_factorization, Eigen::MatrixX3d::Zero(s.rhs.rows(), 3), 5, 1e-6);
  EXPECT_EQ(cg.iterations, 1);
  EXPECT_LT(residual(s.input, cg.solution, s.rhs), 1e-6);
}

TEST(PreconditionedCg, OtherWeightsConvergeAndWarmStartsContinue) {
  const SqueezedSphere s;
  const Eigen::MatrixX3d zero = Eigen::MatrixX3d::Zero(s.rhs.rows(), 3);
  const double start = residual(s.current, zero, s.rhs);
  const ConjugateGradient two = preconditioned_cg(s.current, s.rhs, s.input_factorization, zero, 2, 1e-12);
  EXPECT_EQ(two.iterations, 2);
  EXPECT_NEAR(two.relative_residual, residual(s.current, two.solution, s.rhs), 1e-6);
  EXPECT_LT(two.relative_residual, 0.5 * start);
  // Two more from where the first two stopped (the warm start across
  // iterations) go further, and enough of them solve the system.
  const ConjugateGradient four = preconditioned_cg(s.current, s.rhs, s.input_factorization, two.solution, 2, 1e-12);
  EXPECT_LT(four.relative_residual, two.relative_residual);
  const ConjugateGradient many = preconditioned_cg(s.current, s.rhs, s.input_factorization, zero, 200, 1e-9);
  EXPECT_LT(many.iterations, 200);
  EXPECT_LT(residual(s.current, many.solution, s.rhs), 1e-8);
  // From the solution there is nothing to do.
  const ConjugateGradient again = preconditioned_cg(s.current, s.rhs, s.input_factorization, many.solution, 5, 1e-6);
  EXPECT_EQ(again.iterations, 0);
}

}  // namespace
