#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <fstream>

#include "deform/deform.h"
#include "labels/nearest_labels.h"
#include "refine/refine.h"
#include "mesh/triangulate.h"
#include "io/read_mesh.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

test_meshes::LabelledMesh unit_cube() {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 1, 1, 1);
  return test_meshes::voxel_surface(voxels);
}

PolygonMesh triangulated(const PolygonMesh& mesh) {
  const Triangulation t = triangulate(mesh.vertices, mesh.faces);
  PolygonMesh out;
  out.vertices = mesh.vertices;
  for (Eigen::Index f = 0; f < t.triangles.rows(); ++f) out.faces.add({t.triangles(f, 0), t.triangles(f, 1), t.triangles(f, 2)});
  return out;
}

bool all_faces_have_size(const PolygonMesh& mesh, int size) {
  for (int f = 0; f < mesh.faces.count(); ++f)
    if (mesh.faces.size(f) != size) return false;
  return true;
}

// Distance from p to triangle abc (inside the prism: to the plane; else to the edges).
double distance_to_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                            const Eigen::Vector3d& c) {
  auto segment = [&](const Eigen::Vector3d& s, const Eigen::Vector3d& e) {
    const double t = std::clamp((p - s).dot(e - s) / (e - s).squaredNorm(), 0.0, 1.0);
    return (s + t * (e - s) - p).norm();
  };
  const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
  const Eigen::Vector3d q = p - (p - a).dot(n) * n;
  const bool inside = (b - a).cross(q - a).dot(n) >= 0 && (c - b).cross(q - b).dot(n) >= 0 &&
                      (a - c).cross(q - c).dot(n) >= 0;
  if (inside) return std::abs((p - a).dot(n));
  return std::min({segment(a, b), segment(b, c), segment(c, a)});
}

// Every corner of every child face lies on its parent face (the parent's triangles).
double max_distance_to_parents(const PolygonMesh& input, const Refined& refined) {
  const Triangulation t = triangulate(input.vertices, input.faces);
  double worst = 0.0;
  for (int f = 0; f < refined.mesh.faces.count(); ++f) {
    for (int k = refined.mesh.faces.offsets[f]; k < refined.mesh.faces.offsets[f + 1]; ++k) {
      const Eigen::Vector3d p = refined.mesh.vertices.row(refined.mesh.faces.indices[k]);
      double best = 1e300;
      for (size_t tri = 0; tri < t.face_of_triangle.size(); ++tri)
        if (t.face_of_triangle[tri] == refined.parent_face[f])
          best = std::min(best, distance_to_triangle(p, input.vertices.row(t.triangles(tri, 0)),
                                                     input.vertices.row(t.triangles(tri, 1)),
                                                     input.vertices.row(t.triangles(tri, 2))));
      worst = std::max(worst, best);
    }
  }
  return worst;
}

TEST(Refine, BilinearQuadsStayOnTheSurfaceWithFourToTheKFaces) {
  const auto cube = unit_cube();
  for (int levels : {1, 2, 3}) {
    const Refined r = refine(cube.mesh, cube.labels, levels, RefineScheme::kBilinear);
    EXPECT_EQ(r.mesh.faces.count(), 6 * (1 << (2 * levels)));
    EXPECT_TRUE(all_faces_have_size(r.mesh, 4));
    EXPECT_LT(max_distance_to_parents(cube.mesh, r), 1e-9);
    for (int f = 0; f < r.mesh.faces.count(); ++f) EXPECT_EQ(r.labels[f], cube.labels[r.parent_face[f]]);
  }
}

TEST(Refine, BilinearTrianglesStayTrianglesOnTheSurface) {
  const PolygonMesh sphere = triangulated(test_meshes::uv_sphere(8, 5));
  const std::vector<int> labels = nearest_labels(sphere);
  const Refined r = refine(sphere, labels, 2, RefineScheme::kBilinear);
  EXPECT_EQ(r.mesh.faces.count(), 16 * sphere.faces.count());
  EXPECT_TRUE(all_faces_have_size(r.mesh, 3));
  EXPECT_LT(max_distance_to_parents(sphere, r), 1e-9);
  for (int f = 0; f < r.mesh.faces.count(); ++f) ASSERT_EQ(r.labels[f], labels[r.parent_face[f]]);
  // The input vertices come first and do not move.
  EXPECT_EQ(r.mesh.vertices.topRows(sphere.vertices.rows()), sphere.vertices);
}

TEST(Refine, LoopAndCatmullClarkCountsAndLabels) {
  const PolygonMesh tris = triangulated(unit_cube().mesh);
  std::vector<int> labels = nearest_labels(tris);
  const Refined loop = refine(tris, labels, 3, RefineScheme::kLoop);
  EXPECT_EQ(loop.mesh.faces.count(), 12 * 64);
  EXPECT_TRUE(all_faces_have_size(loop.mesh, 3));
  for (int f = 0; f < loop.mesh.faces.count(); ++f) ASSERT_EQ(loop.labels[f], labels[loop.parent_face[f]]);
  // Smooth schemes pull the corners in.
  EXPECT_LT(loop.mesh.vertices.cwiseAbs().maxCoeff(), 1.0);

  const auto cube = unit_cube();
  const Refined catmark = refine(cube.mesh, cube.labels, 2, RefineScheme::kCatmark);
  EXPECT_EQ(catmark.mesh.faces.count(), 6 * 16);
  EXPECT_TRUE(all_faces_have_size(catmark.mesh, 4));
  const Refined catmark_tris = refine(tris, {}, 2, RefineScheme::kCatmark);
  EXPECT_EQ(catmark_tris.mesh.faces.count(), 12 * 3 * 4);
  EXPECT_TRUE(catmark_tris.labels.empty());
}

TEST(Refine, BadSchemeLevelsAndInputGiveClearErrors) {
  const auto cube = unit_cube();
  EXPECT_THROW(refine(cube.mesh, cube.labels, 0, RefineScheme::kBilinear), Error);
  EXPECT_THROW(refine(cube.mesh, cube.labels, kMaxRefineLevels + 1, RefineScheme::kBilinear), Error);
  EXPECT_THROW(refine(cube.mesh, cube.labels, 1, RefineScheme::kLoop), Error);  // quads
  EXPECT_THROW(parse_refine_scheme("butterfly"), Error);
  EXPECT_THROW(refine(cube.mesh, std::vector<int>(3, 0), 1, RefineScheme::kBilinear), Error);
  try {
    refine(test_meshes::uv_sphere(64, 32), {}, 8, RefineScheme::kCatmark);
    ADD_FAILURE() << "expected the face limit";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fewer levels"), std::string::npos) << e.what();
  }
}

TEST(Refine, RefinedCoarseCubeDeformsIntoAPolycube) {
  // cube.off from libcgal-demo has too few vertices to bend; Loop-refined it
  // is a rounded box whose nearest-axis labels make a clean polycube.
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/cube.off";
  if (!std::ifstream(path).good()) GTEST_SKIP() << path << " missing: run `make data`";
  const PolygonMesh coarse = read_mesh(path);
  const Refined fine = refine(coarse, {}, 3, RefineScheme::kLoop);
  const DeformResult r = deform(fine.mesh, nearest_labels(fine.mesh));
  std::printf("  refined cube: %d faces, it=%d max=%.3f flipped=%d collapsed=%d\n", fine.mesh.faces.count(),
              r.iterations, r.figures.normal_deviation_max_deg, r.figures.flipped_faces, r.figures.collapsed_faces);
  EXPECT_EQ(r.figures.flipped_faces, 0);
  EXPECT_TRUE(r.converged);
}

}  // namespace
