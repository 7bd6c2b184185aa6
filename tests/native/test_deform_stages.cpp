// Each stage of deform() alone (deformation.h, paper_iteration.h and the
// robust stages of robust_run.h), on real models: what it promises, in
// figures.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>

#include "deform/continuous_step.h"
#include "deform/deformation.h"
#include "deform/fit_step.h"
#include "deform/flatten_stage.h"
#include "deform/paper_iteration.h"
#include "deform/relax_stage.h"
#include "deform/robust_run.h"
#include "deform/untangle_step.h"
#include "io/labels_io.h"
#include "io/read_mesh.h"
#include "labels/axis.h"
#include "labels/nearest_labels.h"
#include "mesh/unit_box.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

bool exists(const std::string& path) { return std::ifstream(path).good(); }

// A model in the unit box with its labels, and the options of a run.
struct Case {
  PolygonMesh mesh;
  std::vector<int> labels;
  DeformOptions options;
  IterationCallback callback;
};

Case b0() {
  Case c;
  const std::string dir = std::string(POLYCUBE_SHARED_DATA) + "/B0";
  if (!exists(dir + "/surface.obj")) return c;
  const PolygonMesh mesh = read_mesh(dir + "/surface.obj");
  c.mesh = UnitBoxMesh(mesh).mesh();
  c.labels = read_labels(dir + "/labeling.txt", c.mesh.faces.count());
  return c;
}

Case cgal(const std::string& name) {
  Case c;
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/" + name + ".off";
  if (!exists(path)) return c;
  c.mesh = UnitBoxMesh(read_mesh(path)).mesh();
  c.labels = nearest_labels(c.mesh);
  return c;
}

int count(const std::vector<char>& flags) { return static_cast<int>(std::count(flags.begin(), flags.end(), 1)); }

// The largest deviation of the non-collapsed triangles, and the area-weighted mean.
Figures figures_of(const Deformation& d) { return d.quality.measure(d.x); }

// Fit steps, taken, until fitting ends as robust_iteration() ends it.
int fit(RobustRun& run) {
  int iteration = 0;
  for (double size = 1.0; size >= kFitStepTolerance && iteration < 30;) {
    FoldFreeStep step = fit_step(run);
    size = (step.positions - run.d.x).rowwise().norm().maxCoeff() / run.diagonal;
    run.d.x = std::move(step.positions);
    run.state = std::move(step.states);
    ++iteration;
  }
  return iteration;
}

// A robust run on a case, fitted and flattened as robust_iteration() does
// (Case first: the run refers to its mesh and options).
struct Flattened {
  explicit Flattened(Case model) : c(std::move(model)), d(c.mesh, c.labels, c.options, c.callback), run(d) {
    if (c.mesh.faces.count() == 0) return;
    iteration = fit(run);
    flatten_stage(run, iteration);
  }
  Case c;
  Deformation d;
  RobustRun run;
  int iteration = 0;
};

#define SKIP_IF_MISSING(c) \
  if ((c).mesh.faces.count() == 0) GTEST_SKIP() << "model missing: run `make data` (or shared data absent)"

TEST(DeformStages, DeformationFillsUnlabelledFacesAndMeasuresTheInputWithoutFactorising) {
  Case c = b0();
  SKIP_IF_MISSING(c);
  for (int f = 0; f < c.mesh.faces.count(); f += 7) c.labels[f] = kUnlabelled;
  const Deformation d(c.mesh, c.labels, c.options, c.callback);
  const std::vector<int> nearest = nearest_labels(c.mesh);
  EXPECT_EQ(d.result.unlabelled_faces, (c.mesh.faces.count() + 6) / 7);
  for (int f = 0; f < c.mesh.faces.count(); ++f)
    EXPECT_EQ(d.result.labels[f], f % 7 == 0 ? nearest[f] : c.labels[f]) << f;
  EXPECT_EQ(d.triangle_labels.size(), d.triangulation.face_of_triangle.size());
  EXPECT_GT(d.result.figures.normal_deviation_max_deg, 45.0);  // B0's input is far from its polycube
  EXPECT_EQ(d.result.input_folded_edges, 0);
  EXPECT_EQ(d.factorization.factorizations(), 0);
  EXPECT_TRUE(d.x.isApprox(c.mesh.vertices));
}

TEST(DeformStages, PaperIterationFactorisesOnceWithTheInputsLaplacianAndEveryIterationWithTheCurrent) {
  Case c;
  c.mesh = test_meshes::uv_sphere(32, 16);
  c.labels = nearest_labels(c.mesh);
  c.options.iterations = 8;
  c.options.tolerance_deg = 0.0;
  for (Variant variant : {Variant::kFixed, Variant::kCurrent}) {
    c.options.variant = variant;
    Deformation d(c.mesh, c.labels, c.options, c.callback);
    const double start_mean = d.result.figures.normal_deviation_mean_deg;
    paper_iteration(d);
    EXPECT_EQ(d.result.iterations, 8);
    EXPECT_EQ(d.factorization.factorizations(), variant == Variant::kFixed ? 1 : 8);
    // The sphere's mean deviation, 32 degrees, to about half a degree (its
    // largest needs many more iterations).
    EXPECT_LT(d.result.figures.normal_deviation_mean_deg, 0.03 * start_mean) << variant_name(variant);
  }
}

TEST(DeformStages, FitStepMovesTowardsThePolycubeWithoutFolding) {
  Case c = b0();
  SKIP_IF_MISSING(c);
  Deformation d(c.mesh, c.labels, c.options, c.callback);
  RobustRun run(d);
  EXPECT_EQ(d.factorization.factorizations(), 1);  // the input's Laplacian, once for the whole fit
  const double start_mean = figures_of(d).normal_deviation_mean_deg;
  const FoldFreeStep step = fit_step(run);
  EXPECT_EQ(step.states.flipped_count, 0);
  d.x = step.positions;
  EXPECT_LT(figures_of(d).normal_deviation_mean_deg, 0.5 * start_mean);
  const int iterations = fit(run) + 1;
  EXPECT_LE(iterations, 8);  // B0 fits in 4
  EXPECT_EQ(d.factorization.factorizations(), 1);
  EXPECT_EQ(run.state.flipped_count, 0);
  EXPECT_GT(figures_of(d).normal_deviation_max_deg, 1.0);  // fitted, not exact: flattening's job
}

TEST(DeformStages, FlattenStageMakesEveryChartFlatAndFoldFree) {
  SKIP_IF_MISSING(b0());
  Flattened b0_flat(b0());
  Deformation& d = b0_flat.d;
  RobustRun& run = b0_flat.run;
  const int iteration = b0_flat.iteration;
  ASSERT_TRUE(run.planes);
  EXPECT_EQ(d.result.flat_iteration, iteration);
  ASSERT_FALSE(d.result.flatten_attempts.empty());
  EXPECT_TRUE(d.result.flatten_attempts.back().kept);
  const Figures flat = figures_of(d);
  EXPECT_LT(flat.normal_deviation_max_deg, 1e-6);
  EXPECT_EQ(flat.flipped_faces, 0);
  EXPECT_EQ(flat.folded_edges, 0);
  EXPECT_GT(d.result.collapsed_on_purpose, 0);  // B0: 4 slivers would turn over
  EXPECT_TRUE(d.factorization_released);
  // Once flat, no further attempt.
  const size_t attempts = d.result.flatten_attempts.size();
  flatten_stage(run, iteration + 1);
  EXPECT_EQ(d.result.flatten_attempts.size(), attempts);
}

TEST(DeformStages, FlattenNearUntanglesAPolycubeOfTheSameChartsInsteadOfFitting) {
  SKIP_IF_MISSING(b0());
  Flattened b0_flat(b0());  // a polycube of B0's labels, 4 slivers collapsed
  ASSERT_TRUE(b0_flat.run.planes);
  const int collapsed = count(b0_flat.run.state.collapsed);
  ASSERT_GT(collapsed, 0);
  Case c = b0();
  Deformation d(c.mesh, c.labels, c.options, c.callback);
  RobustRun run(d);
  ASSERT_TRUE(flatten_near(run, b0_flat.d.x, 1));
  EXPECT_EQ(run.flatten_attempts, 0);  // not one of the run's own attempts
  ASSERT_TRUE(run.planes);
  ASSERT_EQ(d.result.flatten_attempts.size(), 1u);
  const DeformResult::FlattenAttempt& attempt = d.result.flatten_attempts.back();
  EXPECT_EQ(attempt.rounds, 0);  // no linear solve
  EXPECT_GT(attempt.untangle_rounds, 0);
  EXPECT_TRUE(attempt.kept);
  EXPECT_EQ(d.result.flat_iteration, 1);
  EXPECT_TRUE(d.factorization_released);
  const Figures near = figures_of(d);
  EXPECT_LT(near.normal_deviation_max_deg, 1e-6);
  EXPECT_EQ(near.flipped_faces, 0);
  EXPECT_EQ(near.folded_edges, 0);
  EXPECT_LT(near.collapsed_faces, collapsed);
  // Once flat, it is not tried again.
  EXPECT_FALSE(flatten_near(run, b0_flat.d.x, 2));
}

TEST(DeformStages, RelaxStageCutsEdgeErrorAndUntanglesWhileStayingExact) {
  SKIP_IF_MISSING(b0());
  Flattened b0_flat(b0());
  Deformation& d = b0_flat.d;
  RobustRun& run = b0_flat.run;
  ASSERT_TRUE(run.planes);
  const Figures flat = figures_of(d);
  int steps = 0;
  while (!run.relaxed && steps < 20 && relax_stage(run, 10 + steps)) ++steps;
  EXPECT_TRUE(run.relaxed);
  EXPECT_GE(steps, 2);
  const Figures relaxed = figures_of(d);
  // B0: edge error 0.0316 -> 0.0311, area error 0.0563 -> 0.0540, the 8
  // collapsed triangles opened.
  EXPECT_LT(relaxed.edge_error, flat.edge_error);
  EXPECT_LT(relaxed.area_error, 0.97 * flat.area_error);
  EXPECT_GT(flat.collapsed_faces, 0);
  EXPECT_LT(relaxed.normal_deviation_max_deg, 1e-6);
  EXPECT_EQ(relaxed.flipped_faces, 0);
  EXPECT_EQ(relaxed.collapsed_faces, 0);  // the slivers collapsed when flattening have their area back
}

TEST(DeformStages, UntangleStepOpensCollapsedSliversInsideTheirCharts) {
  SKIP_IF_MISSING(b0());
  Flattened b0_flat(b0());
  Deformation& d = b0_flat.d;
  RobustRun& run = b0_flat.run;
  ASSERT_TRUE(run.planes);
  const int collapsed = count(run.state.collapsed);
  ASSERT_GT(collapsed, 0);
  const UntangleStep opened = untangle_step(run, d.x, *run.planes, {});
  EXPECT_TRUE(opened.fold_free);
  EXPECT_LT(count(opened.states.collapsed), collapsed);
  EXPECT_LT(d.quality.measure(opened.positions, opened.states).normal_deviation_max_deg, 1e-6);
}

TEST(DeformStages, ContinuousStepGoesOnFoldFreeWhereFlatChartsAreRefused) {
  SKIP_IF_MISSING(cgal("anchor"));
  Flattened anchor(cgal("anchor"));  // its nearest-axis labels never flatten
  Deformation& d = anchor.d;
  RobustRun& run = anchor.run;
  const int iteration = anchor.iteration;
  ASSERT_FALSE(run.planes);
  ASSERT_FALSE(d.result.flatten_attempts.empty());
  const double fitted_mean = figures_of(d).normal_deviation_mean_deg;
  const int flipped = run.state.flipped_count;
  for (int i = 1; i <= 10; ++i) {
    FoldFreeStep step = continuous_step(run, iteration + i);
    d.x = std::move(step.positions);
    run.state = std::move(step.states);
    EXPECT_LE(run.state.flipped_count, flipped) << i;
  }
  EXPECT_LT(figures_of(d).normal_deviation_mean_deg, fitted_mean);
  EXPECT_GT(d.result.stages.current_steps, 0);  // the input's step folds somewhere
  // The input's factorisation, freed while the flat charts were tried and
  // restored once they were refused; none per continuous step.
  EXPECT_FALSE(d.factorization_released);
  EXPECT_EQ(d.factorization.factorizations(), 2);
}

}  // namespace
