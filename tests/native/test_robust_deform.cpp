// The `robust` variant (the default) against its targets (docs/design.md
// section 2.4) on real models, next to the paper's two plain variants.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <fstream>
#include <functional>
#include <optional>
#include <set>
#include <utility>

#include "deform/deform.h"
#include "deform/finished_run.h"
#include "deform/fitted_rotations.h"
#include "deform/fold_free_step.h"
#include "deform/polish_stage.h"
#include "deform/robust_run.h"
#include "io/deform_report.h"
#include "io/labels_io.h"
#include "io/read_mesh.h"
#include "labels/nearest_labels.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"
#include "nearest_flat_start.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

bool exists(const std::string& path) { return std::ifstream(path).good(); }

struct Model {
  PolygonMesh mesh;
  std::vector<int> labels;
};

// A libcgal-demo mesh with nearest-axis labels, or a shared/data model with
// its published labeling. Empty when the file is missing.
Model load(const std::string& name) {
  Model model;
  if (name == "B0" || name == "bone") {
    const std::string dir = std::string(POLYCUBE_SHARED_DATA) + "/" + name;
    if (!exists(dir + "/surface.obj")) return model;
    model.mesh = read_mesh(dir + "/surface.obj");
    model.labels = read_labels(dir + "/labeling.txt", model.mesh.faces.count());
  } else {
    std::string file = name;  // test names cannot hold '-': double_torus_example is double-torus-example
    if (file == "double_torus_example") file = "double-torus-example";
    const std::string path = std::string(POLYCUBE_MESH_DATA) + "/" + file + ".off";
    if (!exists(path)) return model;
    model.mesh = read_mesh(path);
    model.labels = nearest_labels(model.mesh);
  }
  return model;
}

// Two separate right triangles of area 1/2, both facing +Z: small enough to
// check the step control and the figures by hand.
std::pair<Vertices, Triangles> two_triangles() {
  Vertices vertices(6, 3);
  vertices << 0, 0, 0, 1, 0, 0, 0, 1, 0, 5, 5, 0, 6, 5, 0, 5, 6, 0;
  Triangles triangles(2, 3);
  triangles << 0, 1, 2, 3, 4, 5;
  return {vertices, triangles};
}

DeformOptions options(Variant variant, int iterations = 200) {
  DeformOptions o;
  o.variant = variant;
  o.iterations = iterations;
  return o;
}

void print(const std::string& name, const char* variant, const DeformResult& r) {
  std::printf(
      "  %-17s %-7s it=%4d max=%8.3f mean=%7.3f flipped=%4d collapsed=%4d edge=%.3f area=%.3f "
      "relabelled=%zu unconverged=%zu %.2fs\n",
      name.c_str(), variant, r.iterations, r.figures.normal_deviation_max_deg, r.figures.normal_deviation_mean_deg,
      r.figures.flipped_faces, r.figures.collapsed_faces, r.figures.edge_error, r.figures.area_error,
      r.relabelled_faces.size(), r.unconverged_faces.size(), r.seconds.total);
}

// Polygon faces with a corner on an open boundary (an edge of one triangle).
std::set<int> faces_touching_boundary(const PolygonMesh& mesh) {
  const Triangulation tri = triangulate(mesh.vertices, mesh.faces);
  std::map<std::pair<int, int>, int> uses;
  for (Eigen::Index t = 0; t < tri.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = tri.triangles(t, k), b = tri.triangles(t, (k + 1) % 3);
      ++uses[{std::min(a, b), std::max(a, b)}];
    }
  std::set<int> boundary_vertices;
  for (const auto& [edge, count] : uses)
    if (count == 1) boundary_vertices.insert({edge.first, edge.second});
  std::set<int> faces;
  for (Eigen::Index t = 0; t < tri.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (boundary_vertices.count(tri.triangles(t, k))) faces.insert(tri.face_of_triangle[t]);
  return faces;
}

// One row of the table. `gaps` names the targets the row does not
// meet yet ("max": largest normal deviation, "collapsed", "edge", "area":
// edge and area error); every other target is asserted. The notes in
// deform.h (kRobust) say what is left.
struct Row {
  std::string name;
  bool open;
  std::set<std::string> gaps;
};

class ModelTable : public ::testing::TestWithParam<Row> {};

// Targets: zero flipped faces and no more folded edges than the input;
// largest normal deviation below the tolerance (on open meshes: over faces
// not touching the boundary); collapsed faces no more than the plain `fixed`
// variant; edge and area error no larger than the better plain variant.
TEST_P(ModelTable, DefaultMethodMeetsTheTargets) {
  const Row row = GetParam();
  const Model model = load(row.name);
  if (model.mesh.faces.count() == 0) GTEST_SKIP() << row.name << " is missing: run `make data`";
  const DeformResult fixed = deform(model.mesh, model.labels, options(Variant::kFixed));
  const DeformResult current = deform(model.mesh, model.labels, options(Variant::kCurrent));
  DeformOptions defaults;
  defaults.iterations = 200;
  const DeformResult robust = deform(model.mesh, model.labels, defaults);
  print(row.name, "fixed", fixed);
  print(row.name, "current", current);
  print(row.name, variant_name(defaults.variant), robust);
  ::testing::Test::RecordProperty("max_deg", std::to_string(robust.figures.normal_deviation_max_deg));
  ::testing::Test::RecordProperty("iterations", robust.iterations);

  EXPECT_EQ(robust.figures.flipped_faces, 0);
  EXPECT_TRUE(robust.flipped_faces.empty());
  EXPECT_LE(robust.figures.folded_edges, robust.input_folded_edges);
  // A target in `gaps` is not asserted, but the test says when it is met.
  auto target = [&](const std::string& name, bool met) {
    if (!row.gaps.count(name))
      EXPECT_TRUE(met) << name << " target";
    else if (met)
      std::printf("  %s now meets the %s target\n", row.name.c_str(), name.c_str());
  };
  target("collapsed", robust.figures.collapsed_faces <= fixed.figures.collapsed_faces);
  // A thousandth of slack: the figures are means over thousands of faces.
  target("edge", robust.figures.edge_error <= std::min(fixed.figures.edge_error, current.figures.edge_error) + 1e-3);
  target("area", robust.figures.area_error <= std::min(fixed.figures.area_error, current.figures.area_error) + 1e-3);

  std::set<int> boundary;
  if (row.open) boundary = faces_touching_boundary(model.mesh);
  int inside = 0;
  for (int f : robust.unconverged_faces) inside += !boundary.count(f);
  target("max", inside == 0);
  if (!row.gaps.count("max") && !row.open) {
    EXPECT_TRUE(robust.converged);
    EXPECT_LT(robust.figures.normal_deviation_max_deg, 0.5);
  }
}

// The models of docs/design.md section 2.4's table, nearest-axis labels or
// the published ones. The double torus's nearest labels put opposite charts
// side by side: flat, they make fins (folded edges), so the run keeps a
// state without them instead of converging.
INSTANTIATE_TEST_SUITE_P(Robust, ModelTable,
                         ::testing::Values(Row{"larger_sphere", false, {}}, Row{"B0", false, {"collapsed"}},
                                           Row{"fandisk", false, {"collapsed", "edge", "area"}},
                                           Row{"elephant", false, {"max"}},
                                           Row{"mesh_with_border", true, {"collapsed"}},
                                           Row{"bone", false, {"collapsed"}}, Row{"eight", false, {"collapsed"}},
                                           Row{"cactus", false, {"collapsed", "edge", "area"}},
                                           Row{"joint", false, {"edge", "area"}}, Row{"anchor", false, {"max", "area"}},
                                           Row{"double_torus_example", false, {"max", "collapsed", "edge", "area"}}),
                         [](const auto& info) { return info.param.name; });

// A fold-free path, not only a fold-free end: no iteration shows a flipped face.
TEST(Robust, NoFlippedFaceAtAnyIterationOnB0AndTheSphere) {
  for (const std::string name : {"larger_sphere", "B0"}) {
    SCOPED_TRACE(name);
    const Model model = load(name);
    if (model.mesh.faces.count() == 0) GTEST_SKIP() << name << " is missing: run `make data`";
    int iterations = 0, worst = 0;
    const DeformResult r =
        deform(model.mesh, model.labels, options(Variant::kRobust), [&](int, const Vertices&, const Figures& f) {
          ++iterations;
          worst = std::max(worst, f.flipped_faces);
          return true;
        });
    EXPECT_GT(iterations, 0);
    EXPECT_EQ(worst, 0);
    EXPECT_TRUE(r.converged);
    EXPECT_LT(r.figures.max_area_ratio, 2.0);  // no fin: B0 1.4
  }
}

// The largest area ratio, against the scale that keeps the total area: one of
// two equal triangles stretched to three times its area gives ratios 0.5 and
// 1.5 (s^2 = 2), whatever the stretch's direction.
TEST(Robust, LargestAreaRatioIsAgainstTheTotalArea) {
  const auto [from, triangles] = two_triangles();
  const QualityMeasure measure(from, triangles, {4, 4});
  Vertices to = from;
  to.row(5) << 5, 8, 0;  // triangle 1: three times as tall
  const Figures figures = measure.measure(to);
  EXPECT_DOUBLE_EQ(figures.max_area_ratio, 1.5);
  EXPECT_DOUBLE_EQ(figures.area_error, 0.5);
  EXPECT_EQ(measure.measure(to, false).max_area_ratio, 0.0);  // measured with the errors only
}

// The generated shapes the plain method handles: fold-free all the way, and
// exact polycubes, except the torus (quads, nearest-axis labels), which is
// left above the tolerance: some of its quads straddle a polycube edge, bent
// along their diagonal, and no single label lets both triangles reach it
// without one of them turning over (see deform.h).
TEST(Robust, SphereEllipsoidAndTorusStayFoldFree) {
  for (const auto& [name, mesh] : test_meshes::smooth_shapes()) {
    SCOPED_TRACE(name);
    int worst = 0;
    const DeformResult r =
        deform(mesh, nearest_labels(mesh), options(Variant::kRobust), [&](int, const Vertices&, const Figures& f) {
          worst = std::max(worst, f.flipped_faces);
          return true;
        });
    print(name, "robust", r);
    EXPECT_EQ(worst, 0);
    EXPECT_TRUE(r.flipped_faces.empty());
    if (name != "torus 48x24") {
      EXPECT_TRUE(r.converged);
    }
  }
}

// Whatever the labels ask, the robust variant turns no face over at any
// iteration, on the other libcgal-demo models we tried, polygon meshes
// (double-torus-example: quads to heptagons) included.
TEST(Robust, NeverFoldsAFaceOnRealModels) {
  for (const std::string name : {"double-torus-example", "cactus", "anchor", "joint"}) {
    SCOPED_TRACE(name);
    const Model model = load(name);
    if (model.mesh.faces.count() == 0) GTEST_SKIP() << name << " is missing: run `make data`";
    int worst = 0;
    const DeformResult r =
        deform(model.mesh, model.labels, options(Variant::kRobust, 100), [&](int, const Vertices&, const Figures& f) {
          worst = std::max(worst, f.flipped_faces);
          return true;
        });
    print(name, "robust", r);
    EXPECT_EQ(worst, 0);
  }
}

// Stage 8 opens what the nearest labels of organic models collapse: the
// collapsed faces take neighbouring labels, never back to back with an
// opposite one (those edges folded and every further run was refused:
// pig 9.0%, cow 10.2%, dino 24.0% of the area collapsed; docs/design.md
// section 2.6, stage 8).
TEST(Robust, FurtherRunsOpenTheNearestLabelsOfOrganicModels) {
  for (const auto& [name, most] : {std::pair{"pig", 0.005}, {"cow", 0.005}, {"dino", 0.02}}) {
    SCOPED_TRACE(name);
    const Model model = load(name);
    if (model.mesh.faces.count() == 0) GTEST_SKIP() << name << " is missing: run `make data`";
    const DeformResult r = deform(model.mesh, model.labels, options(Variant::kRobust, 50));
    print(name, "robust", r);
    EXPECT_TRUE(r.converged);
    EXPECT_EQ(r.figures.flipped_faces, 0);
    EXPECT_LE(r.figures.folded_edges, r.input_folded_edges);
    EXPECT_GT(r.second_run_iterations, 0);
    EXPECT_LT(r.figures.collapsed_area, most);
  }
}

// Homer's nearest labels put +X beside -X across 3 edges the input bends by
// less than 120 degrees: its runs, the last resort's included, end
// untangled with those edges folded, and none was exact. With the faces
// parted (keep_opposites_apart.h) the run is exact (docs/design.md section
// 2.6, stage 9); without the last resort nothing changes.
TEST(Robust, OppositeNeighboursArePartedWhenNoRunIsExact) {
  const Model model = load("homer");
  if (model.mesh.faces.count() == 0) GTEST_SKIP() << "homer is missing: run `make data`";
  DeformOptions o = options(Variant::kRobust, 50);
  const DeformResult r = deform(model.mesh, model.labels, o);
  print("homer", "robust", r);
  EXPECT_TRUE(r.converged);
  EXPECT_LT(r.figures.normal_deviation_max_deg, o.tolerance_deg);
  EXPECT_EQ(r.figures.flipped_faces, 0);
  EXPECT_LE(r.figures.folded_edges, r.input_folded_edges);
  EXPECT_LT(r.figures.collapsed_area, 0.005);
  EXPECT_GE(r.relabelled_faces.size(), 3u);
  o.last_resort = false;
  EXPECT_FALSE(deform(model.mesh, model.labels, o).converged);
}

// Without retrying refused rounds (the coarse route's coarse run), the
// further runs after a kept run whose rounds were refused go to the
// untangling at once, a single flat solve each. Triceratops, nearest labels:
// every such run's rounds were refused anyway, so the result is the same
// bit for bit; with the default, those runs try their rounds.
TEST(Robust, FurtherRunsAfterRefusedRoundsCanGoStraightToTheUntangling) {
  const Model model = load("triceratops");
  if (model.mesh.faces.count() == 0) GTEST_SKIP() << "triceratops is missing: run `make data`";
  DeformOptions o = options(Variant::kRobust, 50);
  const DeformResult retried = deform(model.mesh, model.labels, o);
  o.retry_refused_rounds = false;
  const DeformResult straight = deform(model.mesh, model.labels, o);
  ASSERT_TRUE(retried.converged);
  EXPECT_TRUE(straight.positions == retried.positions);
  EXPECT_EQ(straight.labels, retried.labels);
  // The same attempts, but those after the refusal: one round each
  // without retrying, more with, then untangled.
  ASSERT_EQ(straight.flatten_attempts.size(), retried.flatten_attempts.size());
  int single = 0;
  for (size_t i = 0; i < straight.flatten_attempts.size(); ++i) {
    const DeformResult::FlattenAttempt &s = straight.flatten_attempts[i], &t = retried.flatten_attempts[i];
    if (s.rounds == t.rounds) continue;
    EXPECT_EQ(s.rounds, 1);
    EXPECT_GT(t.rounds, 1);
    EXPECT_GT(s.untangle_rounds, 0);
    ++single;
  }
  EXPECT_GE(single, 3);
}

TEST(Robust, TheSecondUntanglingWaitsForItsShareOfTheAreaCollapsed) {
  // Stage 5 untangles a result once more where more than
  // untangle_again_above of its area is still collapsed (the turbine,
  // without stages 8 and 10: 9.2% after the first pass, 2.8% after the
  // second). Raised past that share (as the coarse route's coarse run
  // raises it, coarse_to_fine.h), the second pass is not made: one
  // untangling fewer, and the area it reopened stays collapsed.
  const Model model = load("turbine");
  if (model.mesh.faces.count() == 0) GTEST_SKIP() << "turbine is missing: run `make data`";
  DeformOptions o = options(Variant::kRobust, 50);
  o.relabel_collapsed = false;
  o.polish = false;
  const DeformResult again = deform(model.mesh, model.labels, o);
  o.untangle_again_above = 0.5;
  const DeformResult once = deform(model.mesh, model.labels, o);
  ASSERT_TRUE(again.converged);
  ASSERT_TRUE(once.converged);
  EXPECT_EQ(once.stages.untangle.count, again.stages.untangle.count - 1);
  EXPECT_GT(once.figures.collapsed_area, again.figures.collapsed_area);
}

// The local step: input normal onto the axis, then the twist that fits the
// current triangle best.
TEST(Robust, FittedRotationTurnsTheInputNormalOntoTheAxisWithTheBestTwist) {
  Vertices input(3, 3);
  input << 0, 0, 0, 1, 0, 0, 0, 1, 0;  // normal +Z
  Triangles triangle(1, 3);
  triangle << 0, 1, 2;
  const CotangentWeights weights = CotangentWeights::Constant(1, 3, 0.5);
  // The current triangle: the input turned 30 degrees about Z and moved.
  const Eigen::Matrix3d twist = Eigen::AngleAxisd(M_PI / 6, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const Vertices current = ((input * twist.transpose()).rowwise() + Eigen::RowVector3d(2, 3, 4)).eval();
  const Rotations r = fitted_rotations(input, current, triangle, weights, {4});  // +Z
  EXPECT_LT((r[0] - twist).norm(), 1e-12);
  // Label -Y: the normal goes onto -Y, and the twist still fits the current shape.
  const Rotations r2 = fitted_rotations(input, input, triangle, weights, {3});
  EXPECT_LT((r2[0] * Eigen::Vector3d::UnitZ() - Eigen::Vector3d(0, -1, 0)).norm(), 1e-12);
  EXPECT_NEAR(r2[0].determinant(), 1.0, 1e-12);
}

// The step control holds exactly the corners of the triangle a step would turn
// over, and lets the others go the whole way.
TEST(Robust, FoldFreeStepHoldsOnlyWhatWouldFold) {
  const auto [from, triangles] = two_triangles();
  const QualityMeasure measure(from, triangles, {4, 4});
  Vertices to = from;
  to.row(2) << 0, -2, 0;  // turns triangle 0 over (half way too; a quarter is fine)
  to.row(3) << 5, 4, 0;   // triangle 1 just stretches
  const FoldFreeStep step = fold_free_step(from, measure.face_states(from), to, triangles, measure);
  EXPECT_EQ(step.states.flipped_count, 0);
  EXPECT_TRUE(step.held[0]);
  EXPECT_EQ(step.positions.row(3), to.row(3));
  EXPECT_DOUBLE_EQ(step.positions(2, 1), 0.25);
  EXPECT_EQ(step.limited, 3);
}

// A run's steps share the step control's triangles around each vertex: built
// by the first step that folds (none before), and the steps that use it are
// those without it.
TEST(Robust, FoldFreeStepSharesItsIncidence) {
  const auto [from, triangles] = two_triangles();
  const QualityMeasure measure(from, triangles, {4, 4});
  const FaceStates states = measure.face_states(from);
  std::optional<TriangleIncidence> incidence;
  Vertices stretch = from;
  stretch.row(3) << 5, 4, 0;
  fold_free_step(from, states, stretch, triangles, measure, 6, &incidence);
  EXPECT_FALSE(incidence.has_value());  // nothing folded, nothing walked
  Vertices fold = stretch;
  fold.row(2) << 0, -2, 0;
  for (int step = 0; step < 2; ++step) {
    const FoldFreeStep shared = fold_free_step(from, states, fold, triangles, measure, 6, &incidence);
    const FoldFreeStep own = fold_free_step(from, states, fold, triangles, measure, 6);
    ASSERT_TRUE(incidence.has_value());
    EXPECT_EQ(incidence->offsets.back(), 6);
    EXPECT_EQ(shared.positions, own.positions);
    EXPECT_EQ(shared.held, own.held);
    EXPECT_EQ(shared.limited, 3);
  }
}

// The continuous fallback solves the current mesh's Laplacian with the
// input's factorisation (preconditioned_cg.h): once flattening has been tried
// for the last time, further iterations factorise nothing, and every one of
// them is still fold-free. anchor's nearest-axis labels never flatten.
TEST(Robust, ContinuousFallbackFactorisesNothingPerIteration) {
  const Model model = load("anchor");
  if (model.mesh.vertices.rows() == 0) GTEST_SKIP() << "libcgal-demo meshes missing";
  DeformOptions first_run_only = options(Variant::kRobust, 40);
  first_run_only.last_resort = false;  // stage 9 would add a run of its own
  const DeformResult shorter = deform(model.mesh, model.labels, first_run_only);
  first_run_only.iterations = 60;
  const DeformResult longer = deform(model.mesh, model.labels, first_run_only);
  ASSERT_EQ(longer.flatten_attempts.size(), shorter.flatten_attempts.size());
  EXPECT_EQ(longer.iterations, 60);
  EXPECT_GE(longer.stages.current_steps, shorter.stages.current_steps + 15);
  EXPECT_EQ(longer.factorizations, shorter.factorizations);
  EXPECT_EQ(longer.stages.continuous.count + longer.stages.fit.count, 60);
  // A refused attempt refactorises the input's Laplacian on its way out: that
  // is the attempt's, not the iteration's measurement nor its stage's.
  const StageSeconds& s = longer.stages;
  double sum = 0.0;
  for (const StageCost* cost : {&s.set_up, &s.fit, &s.continuous, &s.relax, &s.flatten, &s.untangle, &s.measure}) {
    EXPECT_GE(cost->seconds, 0.0);
    sum += cost->seconds;
  }
  EXPECT_LE(sum, longer.seconds.total);
  EXPECT_EQ(longer.figures.flipped_faces, 0);
  EXPECT_LE(longer.figures.folded_edges, longer.input_folded_edges);
}

// The caller's stop reaches into the untangling, whose rounds take minutes
// at a million triangles: a stop first answered true once the first
// flattening's untangling has begun ends it at its first round, and the run
// with the iteration it is in.
TEST(Robust, StopRequestedEndsAnUntanglingAtItsFirstRound) {
  const Model model = load("bear");  // its first flattening is untangled, in 10 rounds
  if (model.mesh.vertices.rows() == 0) GTEST_SKIP() << "libcgal-demo meshes missing";
  DeformOptions o = options(Variant::kRobust);
  o.relabel_collapsed = false;  // the first run is enough here
  o.polish = false;
  int seen = 0;  // iterations the callback saw
  const IterationCallback count = [&seen](int iteration, const Vertices&, const Figures&) {
    seen = iteration;
    return true;
  };
  const DeformResult whole = deform(model.mesh, model.labels, o, count);
  ASSERT_FALSE(whole.flatten_attempts.empty());
  const DeformResult::FlattenAttempt first = whole.flatten_attempts.front();
  ASSERT_GT(first.iteration, 1);
  ASSERT_GT(first.untangle_rounds, 2);
  // After the callback of the iteration before the attempt, the first
  // question is the end of that iteration's own; the second comes from the
  // untangling.
  int asked = 0;  // questions since then, up to the first true (which stays)
  o.stop_requested = [&] { return asked >= 2 || (seen == first.iteration - 1 && ++asked >= 2); };
  seen = 0;
  const DeformResult stopped = deform(model.mesh, model.labels, o, count);
  EXPECT_TRUE(stopped.stopped);
  EXPECT_EQ(asked, 2);
  EXPECT_EQ(stopped.iterations, first.iteration);
  ASSERT_EQ(stopped.flatten_attempts.size(), 1u);
  EXPECT_EQ(stopped.flatten_attempts[0].untangle_rounds, 1);
  EXPECT_FALSE(stopped.flatten_attempts[0].kept);
  EXPECT_EQ(stopped.figures.flipped_faces, 0);
  EXPECT_LT(stopped.stages.untangle.seconds, 0.5 * whole.stages.untangle.seconds);
}

// The step control's trials ask only whether a shape folds: the same answer
// as comparing full face states.
TEST(Robust, FoldsBeyondAgreesWithFaceStates) {
  const PolygonMesh mesh = test_meshes::uv_sphere(24, 12);
  const Triangles triangles = triangulate(mesh.vertices, mesh.faces).triangles;
  std::vector<int> labels(triangles.rows());
  const std::vector<int> polygon_labels = nearest_labels(mesh);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    labels[t] = polygon_labels[triangulate(mesh.vertices, mesh.faces).face_of_triangle[t]];
  const QualityMeasure measure(mesh.vertices, triangles, labels);
  const FaceStates before = measure.face_states(mesh.vertices);
  int folding = 0;
  for (double noise : {0.0, 0.01, 0.05, 0.2, 0.5}) {
    std::srand(7);
    const Vertices moved = mesh.vertices + noise * Vertices::Random(mesh.vertices.rows(), 3);
    const FaceStates after = measure.face_states(moved);
    bool folds = false;
    for (size_t t = 0; t < after.flipped.size(); ++t) folds |= after.flipped[t] && !before.flipped[t];
    EXPECT_EQ(measure.folds_beyond(moved, before.flipped), folds) << noise;
    // Everything that folds now, allowed: nothing beyond it.
    EXPECT_FALSE(measure.folds_beyond(moved, after.flipped)) << noise;
    folding += folds;
  }
  EXPECT_GE(folding, 2);  // the test sees both answers
}

// A sphere, its triangles' nearest labels and their measure (not copied:
// the measure refers to the triangles).
struct MeasuredSphere {
  const PolygonMesh mesh = test_meshes::uv_sphere(24, 12);
  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  const QualityMeasure measure{mesh.vertices, triangulation.triangles,
                               test_meshes::nearest_triangle_labels(mesh, triangulation)};
};

// A local solve's states are measured again only around what it moved
// (restate_moved): the same states, bit for bit, as measuring the whole
// mesh, whether the new scale moves other triangles across the collapse
// bound or not.
TEST(Robust, RestatedMovedTrianglesAgreeWithTheWholeMesh) {
  const MeasuredSphere sphere;
  const PolygonMesh& mesh = sphere.mesh;
  const Triangles& triangles = sphere.triangulation.triangles;
  const QualityMeasure& measure = sphere.measure;
  // A triangle just above the collapse bound, its corner a pulled to the
  // opposite edge's midpoint: a larger scale collapses it without moving it.
  auto far_from_moves = [](int v) { return v % 11 != 3 && v != 5 && v != 6; };
  Eigen::Index squashed = 0;
  while (!(far_from_moves(triangles(squashed, 0)) && far_from_moves(triangles(squashed, 1)) &&
           far_from_moves(triangles(squashed, 2))))
    ++squashed;
  Vertices start = mesh.vertices;
  const int a = triangles(squashed, 0), b = triangles(squashed, 1), c = triangles(squashed, 2);
  const Eigen::RowVector3d middle = 0.5 * (start.row(b) + start.row(c));
  start.row(a) = middle + 1.05 * kCollapsedAreaRatio * (start.row(a) - middle);
  for (const double push : {0.01, 2.0}) {
    FaceStates states = measure.face_states(start);
    ASSERT_FALSE(states.collapsed[squashed]);
    Vertices moved_x = start;
    std::vector<char> moved_vertex(start.rows(), 0);
    for (int v = 3; v < moved_x.rows(); v += 11) {
      moved_x.row(v) *= 1.0 + push;
      moved_vertex[v] = 1;
    }
    moved_x.row(5) = moved_x.row(6);  // and one triangle collapsed
    moved_vertex[5] = 1;
    std::vector<int> moved;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t)
      if (moved_vertex[triangles(t, 0)] || moved_vertex[triangles(t, 1)] || moved_vertex[triangles(t, 2)])
        moved.push_back(static_cast<int>(t));
    const FaceStates whole = measure.face_states(moved_x);
    measure.restate_moved(moved_x, moved, states);
    EXPECT_EQ(states.area, whole.area);
    EXPECT_EQ(states.deviation_deg, whole.deviation_deg);
    EXPECT_EQ(states.collapsed, whole.collapsed);
    EXPECT_EQ(states.flipped, whole.flipped);
    EXPECT_EQ(states.scale2, whole.scale2);
    EXPECT_EQ(states.flipped_count, whole.flipped_count);
    EXPECT_EQ(states.max_deviation_deg, whole.max_deviation_deg);
    EXPECT_EQ(static_cast<bool>(whole.collapsed[squashed]), push > 1.0);  // the case the test is for
  }
}

// The polish's step control measures again only the triangles around the
// corners a trial moved (rescale_moved), and flags only those and the ones
// pointing against their axis (turned_over): the same flags, scale and
// areas, bit for bit, as measuring the whole mesh.
TEST(Robust, FoldFlagsOfMovedTrianglesAgreeWithTheWholeMesh) {
  const MeasuredSphere sphere;
  const PolygonMesh& mesh = sphere.mesh;
  const Triangles& triangles = sphere.triangulation.triangles;
  const QualityMeasure& measure = sphere.measure;
  TriangleAreas kept;
  std::vector<char> collapsed, flipped;
  measure.fold_flags(mesh.vertices, kept, collapsed, flipped);
  Vertices moved = mesh.vertices;
  std::srand(7);
  int flips = 0;
  for (int v = 0; v < moved.rows(); v += 5) moved.row(v) += 0.5 * Eigen::RowVector3d::Random();
  moved.row(1).setZero();  // collapses the triangles around it towards the centre
  std::vector<int> around;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles(t, k) % 5 == 0 || triangles(t, k) == 1) {
        around.push_back(static_cast<int>(t));
        break;
      }
  std::vector<char> all_collapsed, all_flipped;
  std::vector<double> areas;
  const double scale2 = measure.fold_flags(moved, all_collapsed, all_flipped, &areas);
  EXPECT_EQ(measure.rescale_moved(moved, around, kept), scale2);
  EXPECT_EQ(kept.area, areas);
  // Every triangle's flag from the kept areas; only those moved or pointing
  // against their axis can be turned over.
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    EXPECT_EQ(measure.turned_over(kept, t, scale2), static_cast<bool>(all_flipped[t])) << t;
    if (all_flipped[t]) EXPECT_LT(kept.along[t], 0.0);
  }
  for (char f : all_flipped) flips += f;
  EXPECT_GT(flips, 0);  // the test sees triangles turned over
  // Missing a moved triangle is seen: the areas then differ.
  TriangleAreas stale;
  measure.fold_flags(mesh.vertices, stale, collapsed, flipped);
  around.pop_back();
  measure.rescale_moved(moved, around, stale);
  EXPECT_NE(stale.area, areas);
}

// The polish (deform/polish_stage.h): on B0 and bone with their published
// labels, both errors fall by a tenth or more (B0 0.031/0.054 to
// 0.025/0.042, bone 0.180/0.285 to 0.154/0.242), and the result stays an
// exact polycube with nothing turned over, collapsed or folded beyond the
// run it polished; it is one iteration more.
TEST(Robust, PolishLowersBothErrorsAndKeepsThePolycubeExact) {
  for (const std::string name : {"B0", "bone"}) {
    SCOPED_TRACE(name);
    const Model model = load(name);
    if (model.mesh.faces.count() == 0) GTEST_SKIP() << name << " is missing";
    DeformOptions plain = options(Variant::kRobust);
    plain.polish = false;
    const DeformResult before = deform(model.mesh, model.labels, plain);
    int callbacks = 0;
    const DeformResult after =
        deform(model.mesh, model.labels, options(Variant::kRobust), [&](int, const Vertices&, const Figures&) {
          ++callbacks;
          return true;
        });
    print(name, "plain", before);
    print(name, "polish", after);
    ASSERT_TRUE(before.converged);
    EXPECT_EQ(before.polish_steps, 0);
    EXPECT_GT(after.polish_steps, 0);
    EXPECT_LE(after.polish_steps, kPolishRounds);
    EXPECT_EQ(after.iterations, before.iterations + 1);
    EXPECT_EQ(callbacks, after.iterations);
    EXPECT_TRUE(after.converged);
    EXPECT_LT(after.figures.normal_deviation_max_deg, 1e-6);  // the charts as flat as the run left them
    EXPECT_EQ(after.figures.flipped_faces, 0);
    EXPECT_LE(after.figures.collapsed_faces, before.figures.collapsed_faces);
    EXPECT_LE(after.figures.folded_edges, before.figures.folded_edges);
    EXPECT_LT(after.figures.edge_error, 0.9 * before.figures.edge_error);
    EXPECT_LT(after.figures.area_error, 0.9 * before.figures.area_error);
    EXPECT_EQ(after.labels, before.labels);
  }
}

// The polish on what the run left (finished_run.h: its set-up, its flat
// charts' factors) is the polish on a set-up of its own, bit for bit: B0's
// run ends on the charts the polish solves on, so it factorises nothing.
TEST(Robust, PolishOnTheFinishedRunIsThePolishOnItsOwn) {
  const Model model = load("B0");
  if (model.mesh.faces.count() == 0) GTEST_SKIP() << "B0 is missing";
  const UnitBoxMesh unit(model.mesh);
  const PolygonMesh& mesh = unit.mesh();
  DeformOptions o = options(Variant::kRobust);
  std::unique_ptr<FinishedRun> finished;
  const DeformResult result = deform_in_unit_box(mesh, model.labels, o, {}, finished);
  ASSERT_TRUE(result.converged);
  ASSERT_TRUE(finished && finished->planes);

  DeformOptions from_result = o;
  from_result.start = result.positions;
  Deformation own(mesh, result.labels, from_result, {});
  RobustRun own_run(own);
  const int own_steps = polish_stage(own_run);

  Deformation& d = *finished->deformation;
  d.x = result.positions;
  d.result = DeformResult();
  RobustRun run(d, Assembled{});
  const int steps = polish_stage(run, std::move(finished->planes));

  EXPECT_GT(own_steps, 0);
  EXPECT_EQ(steps, own_steps);
  EXPECT_EQ(own.result.factorizations, 3);
  EXPECT_EQ(d.result.factorizations, 0);
  EXPECT_EQ(d.result.back_substitutions, own.result.back_substitutions);
  EXPECT_TRUE(d.x == own.x);  // bit for bit
  EXPECT_EQ(d.result.figures.edge_error, own.result.figures.edge_error);
  EXPECT_EQ(d.result.figures.area_error, own.result.figures.area_error);
}

// A run from near a polycube (stage 8's further runs at scale, the coarse
// route's fine run) solves with the input's Laplacian only when flatten_near
// is refused: kept, the input is never factorised (the reference timings
// still are, after the run); refused, the run goes on from the input with
// the factorisation it defers, and ends as a run without `near` does.
TEST(Robust, RunFromNearAPolycubeFactorisesTheInputOnlyWhenRefused) {
  const Model model = load("B0");
  if (model.mesh.faces.count() == 0) GTEST_SKIP() << "B0 is missing";
  const UnitBoxMesh unit(model.mesh);
  const PolygonMesh& mesh = unit.mesh();
  DeformOptions o = options(Variant::kRobust);
  o.time_references = true;
  std::unique_ptr<FinishedRun> own_finished, near_finished, refused_finished;
  const DeformResult own = deform_in_unit_box(mesh, model.labels, o, {}, own_finished);
  ASSERT_TRUE(own.converged);
  EXPECT_GT(own_finished->deformation->factorization.factorizations(), 0);

  const DeformResult near =
      deform_in_unit_box(mesh, own.labels, o, {}, near_finished, own.positions, {UntangleStart::local_only});
  EXPECT_TRUE(near.converged);
  EXPECT_EQ(near.flat_iteration, 1);
  EXPECT_EQ(near.figures.flipped_faces, 0);
  EXPECT_LE(near.figures.collapsed_faces, own.figures.collapsed_faces);
  EXPECT_GT(near.reference_factorize_seconds, 0.0);  // made for the reference alone
  EXPECT_TRUE(near.solver.empty());                   // the run itself made none

  // Every vertex at one point: all the area collapsed, refused at once.
  const Vertices point = Vertices::Zero(mesh.vertices.rows(), 3);
  const DeformResult refused =
      deform_in_unit_box(mesh, model.labels, o, {}, refused_finished, point, {UntangleStart::local_only});
  ASSERT_FALSE(refused.flatten_attempts.empty());
  EXPECT_FALSE(refused.flatten_attempts.front().kept);
  EXPECT_EQ(refused.solver, own.solver);
  EXPECT_TRUE(refused.converged);
  EXPECT_TRUE(refused.positions == own.positions);  // bit for bit

  // Near or nothing (the coarse route's runs at full resolution): refused,
  // the run ends there, the input returned, nothing solved with its Laplacian.
  std::unique_ptr<FinishedRun> nothing_finished;
  const DeformResult nothing =
      deform_in_unit_box(mesh, model.labels, o, {}, nothing_finished, point, {UntangleStart::local_only, true});
  EXPECT_FALSE(nothing.converged);
  EXPECT_EQ(nothing.iterations, 0);
  EXPECT_EQ(nothing.flatten_attempts.size(), 1u);
  EXPECT_EQ(nothing.factorizations, 0);
  EXPECT_TRUE(nothing.positions == mesh.vertices);
}

TEST(Robust, IsTheDefault) {
  EXPECT_EQ(DeformOptions{}.variant, Variant::kRobust);
  EXPECT_EQ(parse_variant("robust"), Variant::kRobust);
  EXPECT_STREQ(variant_name(Variant::kRobust), "robust");
}

TEST(Robust, ExactPolycubesStayPut) {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 6, 2, 2);
  test_meshes::add_block(voxels, {0, 2, 0}, 2, 4, 2);
  const test_meshes::LabelledMesh shape = test_meshes::voxel_surface(voxels);
  DeformOptions o = options(Variant::kRobust, 5);
  o.tolerance_deg = 0.0;  // run every iteration
  const DeformResult r = deform(shape.mesh, shape.labels, o);
  EXPECT_EQ(r.iterations, 5);
  EXPECT_LT((r.positions - shape.mesh.vertices).cwiseAbs().maxCoeff(), 1e-9);
  EXPECT_TRUE(r.relabelled_faces.empty());
}

TEST(Robust, ComponentsKeepTheirCentroids) {
  PolygonMesh a = test_meshes::uv_sphere(16, 8), b = test_meshes::uv_sphere(16, 8, Eigen::Vector3d(0.5, 0.5, 0.5));
  PolygonMesh both = a;
  const int nb = static_cast<int>(a.vertices.rows());
  both.vertices.conservativeResize(2 * nb, 3);
  both.vertices.bottomRows(nb) = b.vertices.rowwise() + Eigen::RowVector3d(5, 1, -2);
  for (int f = 0; f < b.faces.count(); ++f) {
    for (int k = b.faces.offsets[f]; k < b.faces.offsets[f + 1]; ++k)
      both.faces.indices.push_back(b.faces.indices[k] + nb);
    both.faces.offsets.push_back(static_cast<int>(both.faces.indices.size()));
  }
  const DeformResult r = deform(both, nearest_labels(both), options(Variant::kRobust, 30));
  EXPECT_LT((r.positions.topRows(nb).colwise().mean() - both.vertices.topRows(nb).colwise().mean()).norm(), 1e-9);
  EXPECT_LT((r.positions.bottomRows(nb).colwise().mean() - both.vertices.bottomRows(nb).colwise().mean()).norm(), 1e-9);
}

// The faces that did not make it are listed by polygon id, in every variant,
// and the JSON report carries them.
TEST(Robust, UnconvergedAndFlippedFacesAreListed) {
  const PolygonMesh mesh = test_meshes::uv_sphere(16, 8);
  const std::vector<int> labels = nearest_labels(mesh);
  const DeformResult early = deform(mesh, labels, options(Variant::kFixed, 1));
  ASSERT_FALSE(early.converged);
  ASSERT_FALSE(early.unconverged_faces.empty());
  EXPECT_TRUE(std::is_sorted(early.unconverged_faces.begin(), early.unconverged_faces.end()));
  for (int f : early.unconverged_faces) {
    EXPECT_GE(f, 0);
    EXPECT_LT(f, mesh.faces.count());
  }
  // Every face turned away from its axis is listed as flipped (and unconverged).
  std::vector<int> opposite = labels;
  opposite[3] ^= 1;
  const DeformResult flipped = deform(mesh, opposite, options(Variant::kFixed, 0));
  EXPECT_EQ(flipped.flipped_faces, std::vector<int>{3});
  EXPECT_TRUE(std::binary_search(flipped.unconverged_faces.begin(), flipped.unconverged_faces.end(), 3));
  const polycube::Json report = deform_report(mesh, flipped, options(Variant::kFixed, 0));
  EXPECT_EQ(report["flipped_face_ids"], polycube::Json::array({3})) << report;
  EXPECT_TRUE(report.contains("unconverged_faces"));
  EXPECT_EQ(report["relabelled_faces"], polycube::Json::array()) << report;

  const DeformResult done = deform(mesh, labels, options(Variant::kRobust));
  ASSERT_TRUE(done.converged);
  EXPECT_TRUE(done.unconverged_faces.empty());
  EXPECT_TRUE(done.flipped_faces.empty());
  // Relabelled faces are listed and their new labels are in `labels`.
  for (int f : done.relabelled_faces) EXPECT_NE(done.labels[f], labels[f]);
}

}  // namespace
