#include <gtest/gtest.h>

#include <fstream>

#include "deform/deform.h"
#include "io/labels_io.h"
#include "io/read_mesh.h"
#include "labels/nearest_labels.h"
#include "test_meshes.h"

namespace {

using namespace polycube;
using test_meshes::LabelledMesh;

bool exists(const std::string& path) { return std::ifstream(path).good(); }

std::string cgal_mesh(const std::string& name) { return std::string(POLYCUBE_MESH_DATA) + "/" + name + ".off"; }

#define SKIP_UNLESS_EXISTS(path) \
  if (!exists(path)) GTEST_SKIP() << path << " is missing: run `make data` (Debian libcgal-demo)"

// Records the figures in the test output (and ctest's XML), so a passing run
// still says how well it did.
void record(const std::string& name, const DeformResult& r) {
  ::testing::Test::RecordProperty(name + "_iterations", r.iterations);
  ::testing::Test::RecordProperty(name + "_max_deg", std::to_string(r.figures.normal_deviation_max_deg));
  ::testing::Test::RecordProperty(name + "_flipped", r.figures.flipped_faces);
  std::printf("  %-28s it=%4d converged=%d max=%8.3f mean=%7.3f edge=%.3f area=%.3f flipped=%d collapsed=%d\n",
              name.c_str(), r.iterations, r.converged, r.figures.normal_deviation_max_deg,
              r.figures.normal_deviation_mean_deg, r.figures.edge_error, r.figures.area_error, r.figures.flipped_faces,
              r.figures.collapsed_faces);
}

void expect_finite_figures(const DeformResult& r) {
  EXPECT_TRUE(r.positions.allFinite());
  EXPECT_GE(r.figures.normal_deviation_max_deg, 0.0);
  EXPECT_LE(r.figures.normal_deviation_max_deg, 180.0);
  EXPECT_TRUE(std::isfinite(r.figures.edge_error));
  EXPECT_TRUE(std::isfinite(r.figures.area_error));
}

DeformOptions options(Variant variant, int iterations = 300, double tolerance = 0.5) {
  DeformOptions o;
  o.variant = variant;
  o.iterations = iterations;
  o.tolerance_deg = tolerance;
  return o;
}

LabelledMesh l_block() {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 6, 2, 2);
  test_meshes::add_block(voxels, {0, 2, 0}, 2, 4, 2);
  return test_meshes::voxel_surface(voxels);
}

LabelledMesh cube_block() {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 4, 4, 4);
  return test_meshes::voxel_surface(voxels);
}

class BothVariants : public ::testing::TestWithParam<Variant> {};
INSTANTIATE_TEST_SUITE_P(Deform, BothVariants, ::testing::Values(Variant::kFixed, Variant::kCurrent),
                         [](const auto& info) { return std::string(variant_name(info.param)); });

TEST_P(BothVariants, ExactPolycubesAreFixedPoints) {
  for (const LabelledMesh& shape : {cube_block(), l_block()}) {
    // Tolerance 0 runs every iteration, so the solve itself must keep the shape.
    const DeformResult r = deform(shape.mesh, shape.labels, options(GetParam(), 5, 0.0));
    EXPECT_EQ(r.iterations, 5);
    EXPECT_LT((r.positions - shape.mesh.vertices).cwiseAbs().maxCoeff(), 1e-9);
    EXPECT_LT(r.figures.normal_deviation_max_deg, 1e-9);
  }
}

TEST_P(BothVariants, NonManifoldOpenNonOrientableAndDegenerateInputStayFinite) {
  std::vector<std::pair<std::string, PolygonMesh>> meshes;
  meshes.emplace_back("moebius", test_meshes::moebius_strip(60, 4));
  PolygonMesh broken = test_meshes::uv_sphere(12, 8);
  broken.faces.add({0, 1, 2});  // a duplicate face
  broken.faces.add({0, 1, 2});
  broken.faces.add({3, 3, 4});     // a zero-area face with a repeated corner
  broken.faces.add({5, 6, 5, 6});  // a flat quad
  meshes.emplace_back("duplicate and zero-area faces", broken);
  PolygonMesh fin = test_meshes::uv_sphere(12, 8);  // a fin on an edge: non-manifold
  const int tip = static_cast<int>(fin.vertices.rows());
  fin.vertices.conservativeResize(tip + 1, 3);
  fin.vertices.row(tip) << 2.0, 0.0, 0.3;
  fin.faces.add({14, 15, tip});
  meshes.emplace_back("non-manifold fin", fin);
  for (const auto& [name, mesh] : meshes) {
    SCOPED_TRACE(name);
    const DeformResult r = deform(mesh, nearest_labels(mesh), options(GetParam(), 100));
    record(name + std::string(" ") + variant_name(GetParam()), r);
    expect_finite_figures(r);
  }
}

TEST_P(BothVariants, RealModelsWithBoundaryAndGenusStayFinite) {
  for (const std::string name : {"mesh_with_border", "eight"}) {
    const std::string path = cgal_mesh(name);
    SKIP_UNLESS_EXISTS(path);
    const PolygonMesh mesh = read_mesh(path);
    const DeformResult r = deform(mesh, nearest_labels(mesh), options(GetParam(), 100));
    record(name + " " + variant_name(GetParam()), r);
    expect_finite_figures(r);
    EXPECT_EQ(r.iterations, 100);
  }
}

// The paper's method, factorised once, on the shapes it handles (docs/design.md section 2).
TEST(DeformFixed, SphereEllipsoidAndTorusBecomePolycubes) {
  for (const auto& [name, mesh] : test_meshes::smooth_shapes()) {
    SCOPED_TRACE(name);
    const DeformResult fixed = deform(mesh, nearest_labels(mesh), options(Variant::kFixed));
    record(name + " fixed", fixed);
    EXPECT_TRUE(fixed.converged);
    EXPECT_LT(fixed.figures.normal_deviation_max_deg, 0.5);
    EXPECT_EQ(fixed.figures.flipped_faces, 0);
    const DeformResult current = deform(mesh, nearest_labels(mesh), options(Variant::kCurrent));
    record(name + " current", current);
    expect_finite_figures(current);
  }
}

// The default variant (the fold-free robust one, docs/design.md section 2.6) on the same shapes. The quad
// torus above, 48 x 24, stays about 3.8 degrees off with it: quads bent across
// a polycube edge (see deform.h); this finer one converges.
TEST(DeformDefault, SphereEllipsoidAndTorusBecomePolycubes) {
  for (const auto& [name, mesh] : test_meshes::smooth_shapes(96, 48)) {
    SCOPED_TRACE(name);
    DeformOptions defaults;
    defaults.iterations = 300;
    const DeformResult r = deform(mesh, nearest_labels(mesh), defaults);
    record(name + " default", r);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(r.figures.normal_deviation_max_deg, 0.5);
    EXPECT_EQ(r.figures.flipped_faces, 0);
  }
}

TEST(DeformFixed, EllipsoidBecomesABoxOfItsProportions) {
  const PolygonMesh mesh = test_meshes::uv_sphere(32, 16, Eigen::Vector3d(1.5, 1.0, 0.7));
  const DeformResult r = deform(mesh, nearest_labels(mesh));
  const Eigen::RowVector3d extent = r.positions.colwise().maxCoeff() - r.positions.colwise().minCoeff();
  EXPECT_GT(extent.x(), extent.y());
  EXPECT_GT(extent.y(), extent.z());
}

TEST(DeformDefault, B0WithItsPublishedLabelingBecomesAPolycube) {
  const std::string dir = std::string(POLYCUBE_SHARED_DATA) + "/B0";
  SKIP_UNLESS_EXISTS(dir + "/surface.obj");
  const PolygonMesh mesh = read_mesh(dir + "/surface.obj");
  const std::vector<int> labels = read_labels(dir + "/labeling.txt", mesh.faces.count());
  const DeformResult r = deform(mesh, labels);
  record("B0 default", r);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.figures.flipped_faces, 0);
  EXPECT_LT(r.figures.normal_deviation_max_deg, 0.5);
  EXPECT_LT(r.figures.edge_error, 0.1);
}

// The report's cost figures (docs/design.md section 4, section 2.6 "Cost"):
// the stages share the run's time without counting any of it twice, every
// iteration is measured once, and the floor's units are there. `fixed`
// back-substitutes once an iteration with its one factorisation; `robust`
// at least once an iteration.
TEST(DeformDefault, B0StagesPartitionTheRunAndCountItsBackSubstitutions) {
  const std::string dir = std::string(POLYCUBE_SHARED_DATA) + "/B0";
  SKIP_UNLESS_EXISTS(dir + "/surface.obj");
  const PolygonMesh mesh = read_mesh(dir + "/surface.obj");
  const std::vector<int> labels = read_labels(dir + "/labeling.txt", mesh.faces.count());
  DeformOptions robust = options(Variant::kRobust);
  robust.time_references = true;
  const DeformResult r = deform(mesh, labels, robust);
  const StageSeconds& s = r.stages;
  EXPECT_EQ(s.set_up.count, 1);
  EXPECT_EQ(s.measure.count, r.iterations);
  EXPECT_EQ(s.fit.count + s.continuous.count + s.relax.count + (r.polish_steps > 0), r.iterations);
  EXPECT_GE(s.flatten.count, 1);
  EXPECT_EQ(s.polish.count, 1);
  EXPECT_GT(r.polish_steps, 0);
  const double sum = s.set_up.seconds + s.fit.seconds + s.continuous.seconds + s.relax.seconds + s.flatten.seconds +
                     s.untangle.seconds + s.measure.seconds + s.polish.seconds;
  for (const StageCost* cost : {&s.set_up, &s.fit, &s.relax, &s.flatten, &s.measure, &s.polish})
    EXPECT_GT(cost->seconds, 0.0);
  EXPECT_LE(sum, r.seconds.total);
  EXPECT_GT(sum, 0.7 * r.seconds.total);  // the rest: the result's own measurement
  EXPECT_GE(r.back_substitutions, r.iterations);
  EXPECT_GT(r.reference_factorize_seconds, r.reference_solve_seconds);
  EXPECT_GT(r.reference_solve_seconds, 0.0);

  const DeformResult fixed = deform(mesh, labels, options(Variant::kFixed, 7, 0.0));
  EXPECT_EQ(fixed.iterations, 7);
  EXPECT_EQ(fixed.factorizations, 1);
  EXPECT_EQ(fixed.back_substitutions, 7);
  EXPECT_EQ(fixed.stages.continuous.count, 7);
  EXPECT_EQ(fixed.stages.measure.count, 7);
}

TEST(Deform, ComponentsKeepTheirCentroidsAndIsolatedVerticesStay) {
  PolygonMesh a = test_meshes::uv_sphere(16, 8), b = test_meshes::uv_sphere(16, 8, Eigen::Vector3d(0.5, 0.5, 0.5));
  PolygonMesh both;
  const int nb = static_cast<int>(a.vertices.rows());
  both.vertices.resize(2 * nb + 1, 3);
  both.vertices.topRows(nb) = a.vertices;
  both.vertices.middleRows(nb, nb) = b.vertices.rowwise() + Eigen::RowVector3d(5, 1, -2);
  both.vertices.row(2 * nb) << 9, 9, 9;  // isolated
  both.faces = a.faces;
  for (int f = 0; f < b.faces.count(); ++f) {
    for (int k = b.faces.offsets[f]; k < b.faces.offsets[f + 1]; ++k)
      both.faces.indices.push_back(b.faces.indices[k] + nb);
    both.faces.offsets.push_back(static_cast<int>(both.faces.indices.size()));
  }
  for (Variant variant : {Variant::kFixed, Variant::kCurrent}) {
    const DeformResult r = deform(both, nearest_labels(both), options(variant, 20));
    expect_finite_figures(r);
    EXPECT_LT((r.positions.topRows(nb).colwise().mean() - both.vertices.topRows(nb).colwise().mean()).norm(), 1e-9);
    EXPECT_LT(
        (r.positions.middleRows(nb, nb).colwise().mean() - both.vertices.middleRows(nb, nb).colwise().mean()).norm(),
        1e-9);
    EXPECT_EQ(r.positions.row(2 * nb), both.vertices.row(2 * nb));
  }
}

TEST(Deform, UnlabelledFacesGetTheNearestAxis) {
  const PolygonMesh mesh = test_meshes::uv_sphere(16, 8);
  std::vector<int> labels(mesh.faces.count(), -1);
  const DeformResult r = deform(mesh, labels, options(Variant::kFixed, 1));
  EXPECT_EQ(r.unlabelled_faces, mesh.faces.count());
  EXPECT_EQ(r.labels, nearest_labels(mesh));
}

TEST(Deform, CallbackSeesEveryIterationAndCanStop) {
  const PolygonMesh mesh = test_meshes::uv_sphere(16, 8);
  std::vector<int> seen;
  const DeformResult r = deform(mesh, nearest_labels(mesh), options(Variant::kFixed, 50, 0.0),
                                [&](int iteration, const Vertices& positions, const Figures&) {
                                  seen.push_back(iteration);
                                  EXPECT_EQ(positions.rows(), mesh.vertices.rows());
                                  return iteration < 3;
                                });
  EXPECT_EQ(seen, (std::vector<int>{1, 2, 3}));
  EXPECT_EQ(r.iterations, 3);
  EXPECT_TRUE(r.stopped);
  EXPECT_FALSE(r.converged);
}

TEST(Deform, MaxDeviationDecreasesOnTheSphere) {
  const PolygonMesh mesh = test_meshes::uv_sphere(32, 16);
  std::vector<double> max_deg;
  deform(mesh, nearest_labels(mesh), options(Variant::kFixed, 30), [&](int, const Vertices&, const Figures& f) {
    max_deg.push_back(f.normal_deviation_max_deg);
    return true;
  });
  ASSERT_GE(max_deg.size(), 5u);
  EXPECT_LT(max_deg.back(), max_deg.front() / 10);
}

TEST(Deform, BadInputIsRejectedWithAMessage) {
  const PolygonMesh sphere = test_meshes::uv_sphere(8, 4);
  const std::vector<int> labels = nearest_labels(sphere);
  auto expect_error = [](const PolygonMesh& mesh, const std::vector<int>& l, const std::string& words) {
    try {
      deform(mesh, l);
      ADD_FAILURE() << "expected an error mentioning '" << words << "'";
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(words), std::string::npos) << e.what();
    }
  };
  expect_error(PolygonMesh{}, {}, "empty");
  PolygonMesh no_faces;
  no_faces.vertices = sphere.vertices;
  expect_error(no_faces, {}, "no faces");
  PolygonMesh nan = sphere;
  nan.vertices(3, 1) = std::nan("");
  expect_error(nan, labels, "non-finite");
  PolygonMesh out_of_range = sphere;
  out_of_range.faces.indices[5] = 1000;
  expect_error(out_of_range, labels, "vertex index 1000");
  std::vector<int> bad = labels;
  bad[2] = 7;
  expect_error(sphere, bad, "outside -1..5");
  expect_error(sphere, std::vector<int>(3, 0), "labels for");
  EXPECT_THROW(parse_variant("fast"), Error);
}

}  // namespace

namespace {

// The paper's `current` variant degenerates armadillo until its Laplacian
// cannot be factorised: the run ends there with the iterations done and the
// reason, instead of throwing them away.
TEST(Deform, SolverBreakdownKeepsTheIterationsDone) {
  const std::string path = cgal_mesh("armadillo");
  SKIP_UNLESS_EXISTS(path);
  const PolygonMesh mesh = read_mesh(path);
  const DeformResult r = deform(mesh, nearest_labels(mesh), options(Variant::kCurrent, 300));
  ASSERT_FALSE(r.failure.empty()) << "armadillo no longer breaks the current variant: find another case";
  EXPECT_NE(r.failure.find("factorisation"), std::string::npos) << r.failure;
  EXPECT_GT(r.iterations, 0);
  EXPECT_LT(r.iterations, 300);
  EXPECT_FALSE(r.converged);
  EXPECT_TRUE(r.positions.allFinite());
}

}  // namespace
