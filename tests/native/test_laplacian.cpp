#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "linear_algebra/laplacian.h"
#include "mesh/triangulate.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

Eigen::MatrixXd dense_laplacian(const Vertices& v, const Triangles& t) {
  Laplacian laplacian(static_cast<int>(v.rows()), t);
  laplacian.assemble(cotangent_weights(v, t));
  return Eigen::MatrixXd(laplacian.matrix());
}

TEST(Laplacian, HandComputedWeightsOfASquare) {
  // Unit square split along (1,3): both triangles are right isosceles, so each
  // side edge has weight cot(45)/2 = 1/2 and the diagonal cot(90) = 0 twice.
  Vertices v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0;
  Triangles t(2, 3);
  t << 0, 1, 3, 1, 2, 3;
  const Eigen::MatrixXd l = dense_laplacian(v, t);
  Eigen::MatrixXd expected(4, 4);
  expected << 1.0, -0.5, 0.0, -0.5,  //
      -0.5, 1.0, -0.5, 0.0,          //
      0.0, -0.5, 1.0, -0.5,          //
      -0.5, 0.0, -0.5, 1.0;
  EXPECT_LT((l - expected).norm(), 1e-14) << l;
}

TEST(Laplacian, EquilateralTriangleWeights) {
  Vertices v(3, 3);
  v << 0, 0, 0, 1, 0, 0, 0.5, std::sqrt(3.0) / 2, 0;
  Triangles t(1, 3);
  t << 0, 1, 2;
  const Eigen::MatrixXd l = dense_laplacian(v, t);
  const double c = 0.5 / std::sqrt(3.0);  // cot(60)/2
  EXPECT_NEAR(l(0, 1), -c, 1e-15);
  EXPECT_NEAR(l(0, 0), 2 * c, 1e-15);
}

TEST(Laplacian, SymmetricRowsSumToZeroAndPositiveSemidefinite) {
  const PolygonMesh sphere = test_meshes::uv_sphere(12, 8);
  const Triangles t = triangulate(sphere.vertices, sphere.faces).triangles;
  const Eigen::MatrixXd l = dense_laplacian(sphere.vertices, t);
  EXPECT_LT((l - l.transpose()).norm(), 1e-13);
  EXPECT_LT(l.rowwise().sum().cwiseAbs().maxCoeff(), 1e-12);
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(l);
  EXPECT_GT(eigen.eigenvalues()[0], -1e-10);
  EXPECT_GT(eigen.eigenvalues()[1], 1e-6) << "one connected component: a one-dimensional null space";
}

TEST(Laplacian, ZeroAreaTrianglesGiveFiniteClampedWeights) {
  Vertices v(4, 3);
  v << 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 0, 0;  // collinear, and a repeated point
  Triangles t(2, 3);
  t << 0, 1, 2, 0, 1, 3;
  const CotangentWeights w = cotangent_weights(v, t);
  EXPECT_TRUE(w.allFinite());
  EXPECT_LE(w.cwiseAbs().maxCoeff(), kMaxCotangent / 2);
  EXPECT_TRUE(dense_laplacian(v, t).allFinite());
}

TEST(Laplacian, ReassemblyReplacesEarlierValuesAndAddsTheShift) {
  const PolygonMesh sphere = test_meshes::uv_sphere(8, 5);
  const Triangles t = triangulate(sphere.vertices, sphere.faces).triangles;
  Laplacian laplacian(static_cast<int>(sphere.vertices.rows()), t);
  const CotangentWeights w = cotangent_weights(sphere.vertices, t);
  laplacian.assemble(w);
  const Eigen::MatrixXd once(laplacian.matrix());
  const double shift = laplacian.assemble(w, 1e-3);
  const Eigen::MatrixXd shifted(laplacian.matrix());
  EXPECT_NEAR(shift, 1e-3 * once.diagonal().mean(), 1e-15);
  EXPECT_LT((shifted - once - shift * Eigen::MatrixXd::Identity(once.rows(), once.cols())).norm(), 1e-13);
}

TEST(Triangulate, ConcavePolygonKeepsItsArea) {
  // An L-shaped hexagon (area 3): a fan from corner 0 would cover outside it.
  PolygonMesh mesh;
  mesh.vertices.resize(6, 3);
  mesh.vertices << 1, 1, 0, 1, 2, 0, 0, 2, 0, 0, 0, 0, 2, 0, 0, 2, 1, 0;
  mesh.faces.add({0, 1, 2, 3, 4, 5});
  const Triangulation tri = triangulate(mesh.vertices, mesh.faces);
  ASSERT_EQ(tri.triangles.rows(), 4);
  double area = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector3d a = mesh.vertices.row(tri.triangles(k, 0)), b = mesh.vertices.row(tri.triangles(k, 1)),
                          c = mesh.vertices.row(tri.triangles(k, 2));
    const double z = (b - a).cross(c - a).z();
    EXPECT_GT(z, 0.0) << "every triangle keeps the polygon's orientation";
    area += 0.5 * z;
  }
  EXPECT_NEAR(area, 3.0, 1e-12);
  EXPECT_EQ(tri.face_of_triangle, std::vector<int>(4, 0));
}

}  // namespace
