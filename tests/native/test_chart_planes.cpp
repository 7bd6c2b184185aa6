// The flat-chart solve (chart_planes.h) and the robust variant's last phase
// built on it (flatten_charts.h).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <set>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "deform/chart_planes.h"
#include "deform/deform.h"
#include "deform/flatten_charts.h"
#include "deform/quality.h"
#include "deform/snap_to_charts.h"
#include "io/read_mesh.h"
#include "labels/axis.h"
#include "labels/nearest_labels.h"
#include "linear_algebra/cotangent_weights.h"
#include "linear_algebra/laplacian.h"
#include "mesh/triangulate.h"
#include "mesh/union_find.h"
#include "nearest_flat_start.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

// What flatten_charts() takes of a mesh with its nearest labels: the
// clamped cotangent Laplacian, shifted, and the quality measure.
struct FlatSetUp {
  explicit FlatSetUp(const PolygonMesh& mesh)
      : n(static_cast<int>(mesh.vertices.rows())),
        t(triangulate(mesh.vertices, mesh.faces)),
        labels(test_meshes::nearest_triangle_labels(mesh, t)),
        quality(mesh.vertices, t.triangles, labels),
        weights(cotangent_weights(mesh.vertices, t.triangles).cwiseMax(0.0)),
        laplacian(n, t.triangles),
        shift(laplacian.assemble(weights, 1e-8)) {}
  int n;
  Triangulation t;
  std::vector<int> labels;
  QualityMeasure quality;
  CotangentWeights weights;
  Laplacian laplacian;
  double shift;
};

struct Block {
  Vertices x;
  Triangles triangles;
  std::vector<int> labels;  // per triangle
};

// An L-shaped block of unit voxels, every vertex moved by up to `noise`.
Block noisy_l_block(double noise) {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 4, 2, 2);
  test_meshes::add_block(voxels, {0, 2, 0}, 2, 3, 2);
  const test_meshes::LabelledMesh shape = test_meshes::voxel_surface(voxels);
  const Triangulation t = triangulate(shape.mesh.vertices, shape.mesh.faces);
  Block s;
  s.x = shape.mesh.vertices + noise * Vertices::Random(shape.mesh.vertices.rows(), 3);
  s.triangles = t.triangles;
  for (Eigen::Index i = 0; i < t.triangles.rows(); ++i) s.labels.push_back(shape.labels[t.face_of_triangle[i]]);
  return s;
}

// How far a triangle's unit normal is from its label's axis (0 when exact).
double worst_normal_error(const Vertices& x, const Block& s) {
  double worst = 0;
  for (Eigen::Index t = 0; t < s.triangles.rows(); ++t) {
    const Eigen::Vector3d a = x.row(s.triangles(t, 0)), b = x.row(s.triangles(t, 1)), c = x.row(s.triangles(t, 2));
    const Eigen::Vector3d n = (b - a).cross(c - a).normalized();
    worst = std::max(worst, (n - label_axis(s.labels[t])).norm());
  }
  return worst;
}

Eigen::SparseMatrix<double> shifted_laplacian(const Block& s, double* shift = nullptr) {
  Laplacian laplacian(static_cast<int>(s.x.rows()), s.triangles);
  const double added = laplacian.assemble(cotangent_weights(s.x, s.triangles).cwiseMax(0.0), 1e-8);
  if (shift) *shift = added;
  return laplacian.matrix();
}

// From a noisy block, the nearest flat-chart shape has every normal exactly
// on its axis, and moves the vertices about as much as the noise.
// The noisy block with one vertex of each chart moved off its plane by
// more than the noise: every chart goes back to the plane most of its
// vertices share, the coordinates off the planes untouched.
TEST(SnapToCharts, PutsEachChartOnTheMedianOfItsVertices) {
  const Block s = noisy_l_block(0.0);
  ChartPlanes planes(static_cast<int>(s.x.rows()), s.triangles, s.labels);
  Vertices moved = s.x;
  std::array<std::vector<int>, 3> unknown;
  for (int axis = 0; axis < 3; ++axis) unknown[axis] = planes.current_unknowns(axis);
  std::array<std::map<int, int>, 3> members;
  for (Eigen::Index v = 0; v < moved.rows(); ++v)
    for (int axis = 0; axis < 3; ++axis) ++members[axis][unknown[axis][v]];
  std::array<std::set<int>, 3> touched;
  for (Eigen::Index v = 0; v < moved.rows(); ++v)
    for (int axis = 0; axis < 3; ++axis)
      if (members[axis][unknown[axis][v]] >= 3 && touched[axis].insert(unknown[axis][v]).second)
        moved(v, axis) += 0.3;
  const Vertices snapped = snap_to_charts(moved, planes);
  EXPECT_LT(worst_normal_error(snapped, s), 1e-12);
  EXPECT_LT((snapped - s.x).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(worst_normal_error(moved, s), 0.1);
}

TEST(ChartPlanes, FlattensEveryChartExactly) {
  const Block s = noisy_l_block(0.05);
  ASSERT_GT(worst_normal_error(s.x, s), 0.01);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  ChartPlanes planes(static_cast<int>(s.x.rows()), s.triangles, s.labels);
  planes.factorize(L);
  const Vertices flat = planes.solve(L * s.x);
  EXPECT_LT(worst_normal_error(flat, s), 1e-12);
  EXPECT_LT((flat - s.x).cwiseAbs().maxCoeff(), 0.2);
  EXPECT_EQ(planes.factorizations(), 3);
}

// An exact polycube is its own nearest flat-chart shape (to the solve's
// precision: the 1e-8 diagonal shift leaves L's condition number near 1e8).
TEST(ChartPlanes, ExactPolycubesStayPut) {
  const Block s = noisy_l_block(0.0);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  ChartPlanes planes(static_cast<int>(s.x.rows()), s.triangles, s.labels);
  planes.factorize(L);
  EXPECT_LT((planes.solve(L * s.x) - s.x).cwiseAbs().maxCoeff(), 1e-7);
}

// A collapsed triangle's corners share a second coordinate: it lies on a
// line; the axis that changed is solved on its charts' factor, merged
// (chart_planes.h), not factorised again.
TEST(ChartPlanes, CollapsePutsATriangleOnALine) {
  const Block s = noisy_l_block(0.05);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  ChartPlanes planes(static_cast<int>(s.x.rows()), s.triangles, s.labels);
  planes.factorize(L);
  const Eigen::Index t = 0;
  const int other = (s.labels[t] / 2 + 1) % 3;
  planes.collapse(t, other);
  planes.factorize(L);
  EXPECT_EQ(planes.factorizations(), 3);
  const Vertices flat = planes.solve(L * s.x);
  const Eigen::Vector3d a = flat.row(s.triangles(t, 0)), b = flat.row(s.triangles(t, 1)),
                        c = flat.row(s.triangles(t, 2));
  EXPECT_LT((b - a).cross(c - a).norm(), 1e-12);
  EXPECT_EQ(a[other], b[other]);
  EXPECT_EQ(a[other], c[other]);
}

// A system with a few collapses, merged onto its charts' factor, has the
// minimiser its own factorisation gives, to rounding, with the joined
// vertices at one value exactly; one with more joins than a merge pays for
// is factorised as before.
TEST(ChartPlanes, FewCollapsesSolveOnTheChartsFactor) {
  const Block s = noisy_l_block(0.05);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  const int n = static_cast<int>(s.x.rows());
  const Eigen::MatrixX3d rhs = L * s.x;
  auto collapsed = [&](ChartPlanes& planes, int count) {
    for (int t = 0; t < count; ++t) planes.collapse(t, (s.labels[t] / 2 + 1) % 3);
    planes.factorize(L);
  };
  for (const int count : {2, static_cast<int>(s.triangles.rows())}) {
    ChartPlanes merged(n, s.triangles, s.labels);
    merged.factorize(L);
    collapsed(merged, count);
    ChartPlanes direct(n, s.triangles, s.labels);
    collapsed(direct, count);
    if (count == 2)
      EXPECT_EQ(merged.factorizations(), 3);
    else
      EXPECT_GT(merged.factorizations(), 3);
    const Vertices a = merged.solve(rhs), b = direct.solve(rhs);
    EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-9 * b.cwiseAbs().maxCoeff());
    for (int axis = 0; axis < 3; ++axis)
      for (int v = 0; v < n; ++v)
        for (int w = v + 1; w < n; ++w)
          if (merged.unknowns(axis)[v] == merged.unknowns(axis)[w]) ASSERT_EQ(a(v, axis), a(w, axis));
  }
}

// At scale too, past the few joins a dense correction can hold: there the
// charts' factor holds them (SparseCholesky::hold_equal), so collapses cost
// no factorisation, and the solution is the collapsed system's own.
TEST(ChartPlanes, AtScaleCollapsesSolveOnTheChartsFactor) {
  const PolygonMesh mesh = test_meshes::uv_sphere(500, 200);
  const int n = static_cast<int>(mesh.vertices.rows());
  const Triangulation t = triangulate(mesh.vertices, mesh.faces);
  const std::vector<int> labels = test_meshes::nearest_triangle_labels(mesh, t);
  Laplacian laplacian(n, t.triangles);
  laplacian.assemble(cotangent_weights(mesh.vertices, t.triangles).cwiseMax(0.0), 1e-8);
  const Eigen::SparseMatrix<double>& L = laplacian.matrix();
  const Eigen::MatrixX3d rhs = L * mesh.vertices;
  // On x and y, whose systems (76,000 unknowns each, z's 46,000) are
  // CHOLMOD's.
  auto collapsed = [&](ChartPlanes& planes) {
    for (Eigen::Index f = 0; f < t.triangles.rows(); f += t.triangles.rows() / 40)
      planes.collapse(f, labels[f] / 2 == 0 ? 1 : 0);
    planes.factorize(L);
  };
  ChartPlanes merged(n, t.triangles, labels);
  merged.factorize(L);
  collapsed(merged);
  ChartPlanes direct(n, t.triangles, labels);
  collapsed(direct);
  const Vertices a = merged.solve(rhs), b = direct.solve(rhs);
#ifdef POLYCUBE_WITH_CHOLMOD
  EXPECT_EQ(merged.factorizations(), 3);  // the charts' alone
#endif
  EXPECT_EQ(direct.factorizations(), 3);
  EXPECT_LT((a - b).cwiseAbs().maxCoeff(), 1e-9 * b.cwiseAbs().maxCoeff());
  for (int axis = 0; axis < 3; ++axis) {
    std::vector<double> value(n, std::numeric_limits<double>::quiet_NaN());
    for (int v = 0; v < n; ++v) {
      double& shared = value[merged.unknowns(axis)[v]];
      if (std::isnan(shared)) shared = a(v, axis);
      ASSERT_EQ(a(v, axis), shared);  // collapsed exactly, not to rounding
    }
  }
}

// The same charts without collapses share the first's factors of the two
// axes it did not collapse and factorise the third with its ordering: the
// same solution bit for bit. release() frees the factors; the next
// factorize() redoes every axis, to the same bits again.
TEST(ChartPlanes, SameChartsShareTheirFactorsAndOrderings) {
  const Block s = noisy_l_block(0.05);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  ChartPlanes planes(static_cast<int>(s.x.rows()), s.triangles, s.labels);
  planes.factorize(L);
  const Vertices expected = planes.solve(L * s.x);
  planes.collapse(0, (s.labels[0] / 2 + 1) % 3);
  planes.factorize(L);
  ChartPlanes again(static_cast<int>(s.x.rows()), s.triangles, s.labels);
  again.use_chart_factors(planes);  // all three: the collapsed axis kept its charts' factor to merge onto
  again.factorize(L);
  EXPECT_EQ(again.factorizations(), 0);
  EXPECT_EQ(again.solve(L * s.x), expected);
  planes.release();  // the shared factors stay with `again`
  EXPECT_EQ(again.solve(L * s.x), expected);
  again.release();
  again.factorize(L);
  EXPECT_EQ(again.factorizations(), 3);
  EXPECT_EQ(again.solve(L * s.x), expected);
}

#ifdef _OPENMP
// Each axis is factorised and solved on a thread of its own
// (chart_planes.cpp): the same solution bit for bit as on one thread, after
// collapses too (two axes refactorised at once).
TEST(ChartPlanes, AxesOnTheirOwnThreadsSolveAsOnOne) {
  const Block s = noisy_l_block(0.05);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  auto solve_with = [&](int threads) {
    const int before = omp_get_max_threads();
    omp_set_num_threads(threads);
    ChartPlanes planes(static_cast<int>(s.x.rows()), s.triangles, s.labels);
    planes.factorize(L);
    std::array<Vertices, 2> x = planes.solve(L * s.x, s.x);
    planes.collapse(0, (s.labels[0] / 2 + 1) % 3);
    planes.collapse(1, (s.labels[1] / 2 + 2) % 3);
    planes.factorize(L);
    x[1] = planes.solve(L * s.x);
    omp_set_num_threads(before);
    return x;
  };
  const std::array<Vertices, 2> one = solve_with(1), two = solve_with(2);
  EXPECT_EQ(one[0], two[0]);
  EXPECT_EQ(one[1], two[1]);
  EXPECT_LT(worst_normal_error(two[0], s), 1e-9);
}
#endif

// Planes built again on the same charts and collapses (the polish of a
// finished run, polish_stage.h) take that run's factors of the axes whose
// unknowns are the same and factorise only the others: the same solution
// bit for bit as factorising all three. An axis collapsed differently is
// not shared, nor are factors a collapse made stale.
TEST(ChartPlanes, SameUnknownsShareTheRunsFactors) {
  const Block s = noisy_l_block(0.05);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  const int n = static_cast<int>(s.x.rows());
  const int other = (s.labels[0] / 2 + 1) % 3;
  ChartPlanes run(n, s.triangles, s.labels);
  run.collapse(0, other);
  run.factorize(L);
  ChartPlanes fresh(n, s.triangles, s.labels);
  fresh.collapse(0, other);
  fresh.factorize(L);
  // New planes on the labels, with or without the run's collapse, sharing its factors.
  auto sharing = [&](bool collapsed) {
    auto planes = std::make_unique<ChartPlanes>(n, s.triangles, s.labels);
    if (collapsed) planes->collapse(0, other);
    planes->share_factors(run);
    planes->factorize(L);
    return planes;
  };
  const auto polish = sharing(true);
  EXPECT_EQ(polish->factorizations(), 0);
  EXPECT_EQ(polish->solve(L * s.x), fresh.solve(L * s.x));
  const auto charts_only = sharing(false);  // `other` without the collapse
  EXPECT_EQ(charts_only->factorizations(), 1);
  ChartPlanes all(n, s.triangles, s.labels);
  all.factorize(L);
  EXPECT_EQ(charts_only->solve(L * s.x), all.solve(L * s.x));
  run.collapse(1, (s.labels[1] / 2 + 2) % 3);  // a collapse not yet factorised: that axis' factor is stale
  const auto stale = sharing(true);
  EXPECT_EQ(stale->factorizations(), 1);
  EXPECT_EQ(stale->solve(L * s.x), fresh.solve(L * s.x));
}

// Each axis' system P^T L P is built without a triplet list (chart_planes.cpp);
// it must be the very matrix setFromTriplets makes of L's entries, to the
// bit, or the factors and every result after them would change: the same
// solve from that matrix, here, gives the same positions exactly.
TEST(ChartPlanes, ReducedSystemsAreTheTripletSumsBitForBit) {
  const Block s = noisy_l_block(0.05);
  const Eigen::SparseMatrix<double> L = shifted_laplacian(s);
  const int n = static_cast<int>(s.x.rows());
  ChartPlanes planes(n, s.triangles, s.labels);
  planes.factorize(L);
  const Eigen::MatrixX3d rhs = L * s.x;
  const Vertices solved = planes.solve(rhs);
  for (int axis = 0; axis < 3; ++axis) {
    // The charts of this axis, numbered by their first vertex.
    UnionFind sets(n);
    for (Eigen::Index t = 0; t < s.triangles.rows(); ++t)
      if (s.labels[t] / 2 == axis) {
        sets.join(s.triangles(t, 0), s.triangles(t, 1));
        sets.join(s.triangles(t, 0), s.triangles(t, 2));
      }
    std::vector<int> of_root(n, -1), unknown(n);
    int m = 0;
    for (int v = 0; v < n; ++v) {
      const int r = sets.root(v);
      if (of_root[r] < 0) of_root[r] = m++;
      unknown[v] = of_root[r];
    }
    std::vector<Eigen::Triplet<double>> entries;
    for (int column = 0; column < L.outerSize(); ++column)
      for (Eigen::SparseMatrix<double>::InnerIterator it(L, column); it; ++it)
        entries.emplace_back(unknown[it.row()], unknown[column], it.value());
    Eigen::SparseMatrix<double> reduced(m, m);
    reduced.setFromTriplets(entries.begin(), entries.end());
    ASSERT_LT(m, n);
    SparseCholesky cholesky;
    cholesky.analyze(reduced);
    cholesky.factorize(reduced);
    Eigen::VectorXd b = Eigen::VectorXd::Zero(m);
    for (int v = 0; v < n; ++v) b[unknown[v]] += rhs(v, axis);
    const Eigen::VectorXd y = cholesky.solve(b);
    for (int v = 0; v < n; ++v) ASSERT_EQ(solved(v, axis), y[unknown[v]]) << "axis " << axis << ", vertex " << v;
  }
}

// Labels that ask for the impossible (the elephant's nearest-axis labels:
// 136 one-face charts) would collapse most of the surface: refused.
TEST(FlattenCharts, RefusesWhatWouldCrushTheModel) {
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/elephant.off";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "elephant.off is missing: run `make data`";
  const PolygonMesh mesh = read_mesh(path);
  const Triangulation t = triangulate(mesh.vertices, mesh.faces);
  const std::vector<int> labels = test_meshes::nearest_triangle_labels(mesh, t);
  const QualityMeasure quality(mesh.vertices, t.triangles, labels);
  const FlatCharts flat = test_meshes::flatten_from_input(mesh, t, labels, quality);
  EXPECT_FALSE(flat.found);
  EXPECT_GT(flat.collapsed_area, DeformOptions{}.max_collapsed_share);
}

// At scale the first solve's factors of the charts alone are kept
// (FlatCharts::charts) for the same charts without collapses later
// (RobustRun::charts_like), and the charts' analyses made ahead
// (ChartPlanes::order) are not made again: the same solutions bit for bit
// as the charts' own factors, with no factorisation for the kept ones.
// Below that scale nothing is kept. A factor made ahead (at most one axis
// of ChartPlanes::factorize) is the flattening's too.
TEST(FlattenCharts, AtScaleTheChartsFactorsAndAnalysesAreKept) {
  for (const auto& [mesh, kept] :
       {std::pair{test_meshes::uv_sphere(32, 16), false}, std::pair{test_meshes::uv_sphere(500, 200), true}}) {
    FlatSetUp set_up(mesh);
    const int n = set_up.n;
    const Triangulation& t = set_up.t;
    const std::vector<int>& labels = set_up.labels;
    const Eigen::SparseMatrix<double>& L = set_up.laplacian.matrix();
    ChartPlanes ordered(n, t.triangles, labels);
    ordered.order(L);
    ChartPlanes from_orderings(n, t.triangles, labels);
    from_orderings.use_orderings(ordered);
    ordered.factorize(L, 1);  // the largest system only, as beside the fitting (RobustRun)
    EXPECT_EQ(ordered.factorizations(), 1);
    const FlatCharts flat = flatten_charts(
        mesh.vertices, mesh.vertices, t.triangles, labels, set_up.weights, L, set_up.shift, set_up.quality,
        [](const Eigen::MatrixX3d& y) { return y; }, 1.0, 1, &ordered);
    EXPECT_EQ(flat.planes->factorizations(), 2);  // the third is ordered's
    ASSERT_EQ(flat.charts != nullptr, kept) << n;
    ChartPlanes own(n, t.triangles, labels);
    own.factorize(L);
    const Eigen::MatrixX3d b = L * mesh.vertices;
    const Vertices expected = own.solve(b);
    from_orderings.factorize(L);
    EXPECT_EQ(from_orderings.factorizations(), 3);
    EXPECT_EQ(from_orderings.solve(b), expected);
    if (!kept) continue;
    ChartPlanes shared(n, t.triangles, labels);
    shared.use_chart_factors(*flat.charts);
    shared.factorize(L);
    EXPECT_EQ(shared.factorizations(), 0);
    EXPECT_EQ(shared.solve(b), expected);
  }
}

// A first flat solve that turns over more than kHopelessFlippedShare of the
// triangles ends the attempt when the caller asks (the coarse route's
// hand-over): unflat, the same first solve.
TEST(FlattenCharts, GivesUpAHopelessAttemptAfterItsFirstSolve) {
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/armadillo.off";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "armadillo.off is missing: run `make data`";
  const PolygonMesh mesh = read_mesh(path);
  FlatSetUp s(mesh);
  const auto flatten = [&](bool give_up_hopeless) {
    return flatten_charts(
        mesh.vertices, mesh.vertices, s.t.triangles, s.labels, s.weights, s.laplacian.matrix(), s.shift, s.quality,
        [](const Eigen::MatrixX3d& y) { return y; }, 1.0, kFlattenRounds, nullptr, give_up_hopeless);
  };
  const FlatCharts hopeless = flatten(true);
  EXPECT_FALSE(hopeless.found);
  EXPECT_EQ(hopeless.rounds, 1);
  EXPECT_GT(hopeless.states.flipped_count, kHopelessFlippedShare * static_cast<double>(s.t.triangles.rows()));
  // Without, the rounds go on (here, no bound on the collapsed area, to a
  // flat shape that collapses what it must).
  const FlatCharts tried = flatten(false);
  EXPECT_GT(tried.rounds, 1);
  EXPECT_EQ(tried.first_positions, hopeless.first_positions);
}

// Once the robust variant has flattened the charts, every later iteration
// (the relaxation) is an exact polycube with nothing folded, and relaxing
// does not raise the edge error; opening collapsed triangles
// (untangle_flat_charts.h) may, in the iteration that lowers their count.
TEST(FlattenCharts, RelaxationStaysExactAndFoldFree) {
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/mesh_with_border.off";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "mesh_with_border.off is missing: run `make data`";
  const PolygonMesh mesh = read_mesh(path);
  DeformOptions options;
  options.iterations = 200;
  // One run's relaxation: a kept further run of stage 8 (docs/design.md
  // section 2.6) would be the result, seen once, flat in its last iteration.
  options.relabel_collapsed = false;
  std::vector<Figures> seen;
  const DeformResult r = deform(mesh, nearest_labels(mesh), options, [&](int, const Vertices&, const Figures& f) {
    seen.push_back(f);
    return true;
  });
  ASSERT_TRUE(r.converged);
  ASSERT_GT(r.flat_iteration, 0);
  ASSERT_GT(r.iterations, r.flat_iteration);  // it relaxed
  double edge = seen[r.flat_iteration - 1].edge_error;
  for (size_t i = r.flat_iteration - 1; i < seen.size(); ++i) {
    EXPECT_EQ(seen[i].normal_deviation_max_deg, 0.0);
    EXPECT_EQ(seen[i].flipped_faces, 0);
    const bool opened = i > 0 && seen[i].collapsed_faces < seen[i - 1].collapsed_faces;
    if (!opened) {
      EXPECT_LE(seen[i].edge_error, edge + 1e-9);
    }
    edge = seen[i].edge_error;
  }
  EXPECT_LT(r.figures.edge_error, 0.9 * seen[r.flat_iteration - 1].edge_error);
}

}  // namespace
