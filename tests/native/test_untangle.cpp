// The untangling stage (deform/untangle_flat_charts.h) and its minimiser
// (linear_algebra/minimize_lbfgs.h): collapsed and turned-over triangles of a
// flat polycube get their area back, every chart stays flat on its axis, and
// chart planes move where the triangles need room.
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <functional>
#include <set>

#include "deform/quality.h"
#include "deform/untangle_flat_charts.h"
#include "linear_algebra/minimize_lbfgs.h"
#include "mesh/triangulate.h"
#include "test_meshes.h"

namespace polycube {
namespace {

// Rosenbrock's function, its minimum 0 at (1, 1) along a curved valley.
double rosenbrock(const Eigen::VectorXd& x, Eigen::VectorXd& g) {
  const double a = 1.0 - x[0], b = x[1] - x[0] * x[0];
  g.resize(2);
  g[0] = -2.0 * a - 400.0 * x[0] * b;
  g[1] = 200.0 * b;
  return a * a + 100.0 * b * b;
}

TEST(MinimizeLbfgs, FindsTheRosenbrockMinimum) {
  Eigen::VectorXd x(2);
  x << -1.2, 1.0;
  const LbfgsResult r = minimize_lbfgs(rosenbrock, x, 500, 1e-10, 0.0);
  EXPECT_TRUE(r.converged);
  EXPECT_NEAR(x[0], 1.0, 1e-6);
  EXPECT_NEAR(x[1], 1.0, 1e-6);
  EXPECT_LT(r.iterations, 200);
}

// A stop is polled before the first iteration and ends the minimisation
// there; one that never answers true changes nothing.
TEST(MinimizeLbfgs, StopsWhenAsked) {
  const Eigen::Vector2d start(-1.2, 1.0);
  Eigen::VectorXd x = start;
  LbfgsResult r = minimize_lbfgs(rosenbrock, x, 500, 1e-10, 0.0, kLbfgsMemory, [] { return true; });
  EXPECT_TRUE(r.stopped);
  EXPECT_EQ(r.iterations, 0);
  EXPECT_TRUE(x == start);
  Eigen::VectorXd y = start;
  r = minimize_lbfgs(rosenbrock, y, 500, 1e-10, 0.0, kLbfgsMemory, [] { return false; });
  x = start;
  const LbfgsResult plain = minimize_lbfgs(rosenbrock, x, 500, 1e-10, 0.0);
  EXPECT_FALSE(r.stopped);
  EXPECT_EQ(r.iterations, plain.iterations);
  EXPECT_TRUE(x == y);
}

struct Block {
  Vertices vertices;
  Triangles triangles;
  std::vector<int> labels;  // per triangle
};

// A 4 x 4 x 2 (or nx x ny x nz) block of voxels, triangulated: an exact polycube of itself.
Block block(int nx = 4, int ny = 4, int nz = 2) {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, nx, ny, nz);
  const test_meshes::LabelledMesh m = test_meshes::voxel_surface(voxels);
  const Triangulation t = triangulate(m.mesh.vertices, m.mesh.faces);
  Block b{m.mesh.vertices, t.triangles, {}};
  for (int f : t.face_of_triangle) b.labels.push_back(m.labels[f]);
  return b;
}

// Every triangle on a plane of its label's axis: its corners share that coordinate.
bool flat(const Vertices& x, const Block& b) {
  for (Eigen::Index t = 0; t < b.triangles.rows(); ++t) {
    const int axis = b.labels[t] / 2;
    for (int k = 1; k < 3; ++k)
      if (std::abs(x(b.triangles(t, k), axis) - x(b.triangles(t, 0), axis)) > 1e-12) return false;
  }
  return true;
}

TEST(UntangleFlatCharts, OpensTurnedOverAndCollapsedTriangles) {
  const Block b = block();
  Vertices tangled = b.vertices;
  // The top's (z = 2) inner vertices: one pushed across its neighbours (its
  // triangles turn over), one onto its neighbour (they collapse).
  int pushed = -1, crushed = -1;
  for (Eigen::Index v = 0; v < tangled.rows(); ++v) {
    if (tangled(v, 2) != 2.0) continue;
    if (tangled(v, 0) == 1.0 && tangled(v, 1) == 1.0) pushed = static_cast<int>(v);
    if (tangled(v, 0) == 3.0 && tangled(v, 1) == 2.0) crushed = static_cast<int>(v);
  }
  ASSERT_GE(pushed, 0);
  ASSERT_GE(crushed, 0);
  tangled(pushed, 0) = 2.6;
  tangled(crushed, 0) = 2.0;
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  const FaceStates before = quality.face_states(tangled);
  ASSERT_GT(before.flipped_count, 0);
  ASSERT_TRUE(flat(tangled, b));

  const UntangledCharts u = untangle_flat_charts(b.vertices, tangled, b.triangles, b.labels);
  EXPECT_TRUE(u.untangled);
  EXPECT_EQ(u.put_on_a_line, 0);
  EXPECT_TRUE(flat(u.positions, b));
  const Figures after = quality.measure(u.positions);
  EXPECT_EQ(after.flipped_faces, 0);
  EXPECT_EQ(after.collapsed_faces, 0);
  EXPECT_LT(after.normal_deviation_max_deg, 1e-9);
  EXPECT_EQ(after.folded_edges, 0);
}

TEST(UntangleFlatCharts, MovesAChartPlaneToGiveItsNeighboursRoom) {
  const Block b = block();
  Vertices squeezed = b.vertices;
  // The block pressed flat: the sides collapse; the top is one plane
  // unknown and must rise again.
  squeezed.col(2) *= 1e-5;
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  ASSERT_GT(quality.measure(squeezed).collapsed_faces, 0);

  const UntangledCharts u = untangle_flat_charts(b.vertices, squeezed, b.triangles, b.labels);
  EXPECT_TRUE(u.untangled);
  EXPECT_TRUE(flat(u.positions, b));
  const Figures after = quality.measure(u.positions);
  EXPECT_EQ(after.collapsed_faces, 0);
  EXPECT_EQ(after.flipped_faces, 0);
  // Height over width back near the input's 2 / 4.
  const Eigen::RowVector3d size = u.positions.colwise().maxCoeff() - u.positions.colwise().minCoeff();
  EXPECT_NEAR(size[2] / size[0], 0.5, 0.1);
  EXPECT_LT(after.area_error, 0.1);
}

TEST(UntangleFlatCharts, LocalRoundsKeepTheContract) {
  // A triangle of the block's -X side labelled +X: flat on the same plane
  // as its neighbours, facing the other way, it has no room round after
  // round (the case the local rounds are for) until it is put on a line.
  Block b = block();
  const auto relabelled = std::find(b.labels.begin(), b.labels.end(), 1);
  ASSERT_NE(relabelled, b.labels.end());
  *relabelled = 0;
  ASSERT_TRUE(flat(b.vertices, b));
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  const UntangledCharts global = untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels, 30, 0.0);
  const UntangledCharts local = untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels, 30, 1.0);
  EXPECT_EQ(global.local_rounds, 0);
  EXPECT_GT(local.local_rounds, 0);
  EXPECT_EQ(local.put_on_a_line, global.put_on_a_line);
  EXPECT_TRUE(local.untangled);
  EXPECT_TRUE(flat(local.positions, b));
  const Figures g = quality.measure(global.positions), l = quality.measure(local.positions);
  EXPECT_EQ(l.flipped_faces, 0);
  EXPECT_LE(l.collapsed_faces, g.collapsed_faces);
  EXPECT_LE(l.folded_edges, g.folded_edges);
  EXPECT_LT(l.area_error, g.area_error + 0.01);
  EXPECT_LT(l.edge_error, g.edge_error + 0.01);
}

TEST(UntangleFlatCharts, RoundsGoLocalForAFewTrianglesWithoutRoomNotForAShareOfThem) {
  // The block's 128 triangles: one without room is under 1% of them, and
  // the default rounds go local for it; two are over 1% (a region whose
  // planes may still have to move on a mesh this small) and stay global.
  // Before the count rule, rounds went local only under 0.2% of the
  // triangles: never on a mesh under 500 triangles.
  Block one = block();
  ASSERT_EQ(one.triangles.rows(), 128);
  Block two = one;
  const auto first = std::find(one.labels.begin(), one.labels.end(), 1);
  ASSERT_NE(first, one.labels.end());
  *first = 0;
  auto in_two = two.labels.begin() + (first - one.labels.begin());
  *in_two = 0;
  const auto second = std::find(two.labels.rbegin(), two.labels.rend(), 3);  // a -Y triangle, far from the -X one
  ASSERT_NE(second, two.labels.rend());
  *second = 2;
  const UntangledCharts a = untangle_flat_charts(one.vertices, one.vertices, one.triangles, one.labels);
  int before_global = 0;  // called once, before the first of several global rounds
  const UntangledCharts b = untangle_flat_charts(two.vertices, two.vertices, two.triangles, two.labels, kUntangleRounds,
                                                 kUntangleLocalShare, {}, UntangleMinimiser::automatic, {},
                                                 [&] { ++before_global; });
  EXPECT_GT(b.rounds, 1);
  EXPECT_EQ(before_global, 1);
  EXPECT_GT(a.local_rounds, 0);
  EXPECT_EQ(a.put_on_a_line, 1);
  EXPECT_EQ(b.local_rounds, 0);
  EXPECT_EQ(b.put_on_a_line, 2);
  EXPECT_TRUE(a.untangled);
  EXPECT_TRUE(b.untangled);
}

// Newton's rounds (the minimiser from 100,000 triangles on) on `crushed`,
// a flat map of `b` that turns nothing over: every round local, every
// triangle given room, the charts flat, and each vertex `far` says the
// local rings cannot reach exactly where the caller put it. Returns how
// many vertices were far.
int expect_opened_locally(const Block& b, const Vertices& crushed, const std::function<bool(Eigen::Index)>& far) {
  int before_global = 0;  // local rounds alone: the caller's factors are never freed (untangle_step.h)
  const UntangledCharts u =
      untangle_flat_charts(b.vertices, crushed, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, {},
                           UntangleMinimiser::newton, {}, [&] { ++before_global; });
  EXPECT_EQ(before_global, 0);
  EXPECT_TRUE(u.untangled);
  EXPECT_EQ(u.put_on_a_line, 0);
  EXPECT_GT(u.rounds, 0);
  EXPECT_EQ(u.local_rounds, u.rounds);
  EXPECT_TRUE(flat(u.positions, b));
  const Figures after = QualityMeasure(b.vertices, b.triangles, b.labels).measure(u.positions);
  EXPECT_EQ(after.collapsed_faces, 0);
  EXPECT_EQ(after.flipped_faces, 0);
  int count = 0;
  for (Eigen::Index v = 0; v < crushed.rows(); ++v) {
    if (!far(v)) continue;
    ++count;
    EXPECT_EQ(u.positions.row(v), crushed.row(v));
  }
  return count;
}

TEST(UntangleFlatCharts, AFewSliversAreOpenedLocallyAndTheRestOfTheMapKept) {
  // A 16 x 16 x 8 block (2,048 triangles) whose top has one vertex moved
  // onto its neighbour: the two triangles between them collapse, a few
  // stretch. Newton's rounds (the minimiser from 100,000 triangles on)
  // start local and end once those have room: every vertex beyond the
  // local rings stays where the caller put it, bit for bit (a global round
  // would move the whole map).
  const Block b = block(16, 16, 8);
  ASSERT_EQ(b.triangles.rows(), 2048);
  Vertices crushed = b.vertices;
  int moved = -1;
  for (Eigen::Index v = 0; v < crushed.rows(); ++v)
    if (crushed(v, 0) == 8.0 && crushed(v, 1) == 8.0 && crushed(v, 2) == 8.0) moved = static_cast<int>(v);
  ASSERT_GE(moved, 0);
  crushed(moved, 0) = 9.0;
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  ASSERT_GT(quality.measure(crushed).collapsed_faces, 0);
  ASSERT_TRUE(flat(crushed, b));

  const int far = expect_opened_locally(b, crushed, [&](Eigen::Index v) {
    return (b.vertices.row(v) - b.vertices.row(moved)).lpNorm<Eigen::Infinity>() > 4.0;
  });
  EXPECT_GT(far, 900);  // of 1,026
}

// The block with the vertices of its top (at height `top`) that `pick`
// chooses by their x and y moved by `dx` along x; `moved` counts them.
Vertices top_moved(const Block& b, double top, const std::function<bool(double, double)>& pick, double dx,
                   int& moved) {
  Vertices x = b.vertices;
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    if (x(v, 2) == top && pick(x(v, 0), x(v, 1))) x(v, 0) += dx, ++moved;
  return x;
}

TEST(UntangleFlatCharts, ManySliversAtScaleAreOpenedLocallyToo) {
  // The block of the test above with fifteen vertices of its top moved
  // onto their neighbours: thirty triangles collapse, more than the few
  // (1% of 2,048) for which rounds go local on their own. Nothing is
  // turned over, so Newton's rounds are all local all the same, and the
  // bottom of the block, beyond every local ring, stays where the caller
  // put it bit for bit (a global round, as the rounds were until the
  // triangles without room were few, moves the whole map).
  const Block b = block(16, 16, 8);
  int moved = 0;
  const Vertices crushed = top_moved(
      b, 8.0, [](double x, double y) { return (x == 2.0 || x == 6.0 || x == 10.0) && std::fmod(y, 3.0) == 2.0; }, 1.0,
      moved);
  ASSERT_EQ(moved, 15);
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  ASSERT_GT(quality.measure(crushed).collapsed_faces, 20);
  ASSERT_EQ(quality.measure(crushed).flipped_faces, 0);
  ASSERT_TRUE(flat(crushed, b));

  const int far = expect_opened_locally(b, crushed, [&](Eigen::Index v) { return crushed(v, 2) <= 3.0; });
  EXPECT_GT(far, 300);
}

// The block with the vertex at the middle of its top moved past its
// neighbour: the triangles around it turn over.
Vertices top_vertex_moved_past_its_neighbour(const Block& b) {
  Vertices crushed = b.vertices;
  for (Eigen::Index v = 0; v < crushed.rows(); ++v)
    if (crushed(v, 0) == 8.0 && crushed(v, 1) == 8.0 && crushed(v, 2) == 8.0) crushed(v, 0) = 9.5;
  return crushed;
}

TEST(UntangleFlatCharts, LocalThenGlobalOpensTurnedOverTrianglesLocallyThenFinishesWithOneGlobalRound) {
  // The block with a vertex of its top moved past its neighbour: triangles
  // turn over, so Newton's rounds would be global from the start. With
  // `local_then_global` (stage 8's runs from the result) they are local
  // until every triangle has room, then one global round finishes.
  const Block b = block(16, 16, 8);
  const Vertices crushed = top_vertex_moved_past_its_neighbour(b);
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  ASSERT_GT(quality.measure(crushed).flipped_faces, 0);
  ASSERT_TRUE(flat(crushed, b));
  int before_global = 0;
  const UntangledCharts u =
      untangle_flat_charts(b.vertices, crushed, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, {},
                           UntangleMinimiser::newton, {}, [&] { ++before_global; },
                           UntangleStart::local_then_global);
  EXPECT_TRUE(u.untangled);
  EXPECT_GT(u.local_rounds, 0);
  EXPECT_EQ(u.rounds, u.local_rounds + 1);
  EXPECT_EQ(before_global, 1);
  EXPECT_TRUE(flat(u.positions, b));
  const Figures after = quality.measure(u.positions);
  EXPECT_EQ(after.flipped_faces, 0);
  EXPECT_EQ(after.collapsed_faces, 0);
  // A map whose every triangle has room is returned as it is.
  const UntangledCharts same = untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels, kUntangleRounds,
                                                    kUntangleLocalShare, {}, UntangleMinimiser::newton, {}, {},
                                                    UntangleStart::local_then_global);
  EXPECT_TRUE(same.untangled);
  EXPECT_EQ(same.rounds, 0);
  EXPECT_EQ(same.positions, b.vertices);
}

TEST(UntangleFlatCharts, LocalOnlyOpensTurnedOverTrianglesWithoutAGlobalRound) {
  // The same crushed block: with `local_only` (a coarse polycube carried
  // back) the local rounds open it and nothing else moves, no global round
  // (and no factor of the whole mesh) after them.
  const Block b = block(16, 16, 8);
  const Vertices crushed = top_vertex_moved_past_its_neighbour(b);
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  ASSERT_GT(quality.measure(crushed).flipped_faces, 0);
  int before_global = 0;
  const UntangledCharts u =
      untangle_flat_charts(b.vertices, crushed, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, {},
                           UntangleMinimiser::newton, {}, [&] { ++before_global; }, UntangleStart::local_only);
  EXPECT_TRUE(u.untangled);
  EXPECT_GT(u.local_rounds, 0);
  EXPECT_EQ(u.rounds, u.local_rounds);
  EXPECT_EQ(before_global, 0);
  EXPECT_TRUE(flat(u.positions, b));
  const Figures after = quality.measure(u.positions);
  EXPECT_EQ(after.flipped_faces, 0);
  EXPECT_EQ(after.collapsed_faces, 0);
  // Far from the moved vertex the map is the caller's, up to the rounding
  // of its round trip through the unknowns.
  double far_moved = 0.0;
  for (Eigen::Index v = 0; v < crushed.rows(); ++v)
    if (std::abs(b.vertices(v, 0) - 8.0) + std::abs(b.vertices(v, 1) - 8.0) > 8.0)
      far_moved = std::max(far_moved, (u.positions.row(v) - crushed.row(v)).norm());
  EXPECT_LT(far_moved, 1e-12);
}

TEST(UntangleFlatCharts, ALargeLocalRoundStartsWithLbfgsAndNewtonFinishes) {
  // A 230 x 230 x 1 block whose top (105,800 triangles) has every fourth
  // vertex of every fourth row moved past its neighbour: the triangles
  // around each turn over, as where the coarse route's polycube is carried
  // to the fine mesh, and the first local round holds the whole top.
  // Newton's first steps there are cut short by the line search, a
  // factorisation each; L-BFGS's iterations first leave Newton a few.
  const Block b = block(230, 230, 1);
  int moved = 0;
  const Vertices crushed = top_moved(
      b, 1.0, [](double x, double y) { return std::fmod(x, 4.0) == 2.0 && std::fmod(y, 4.0) == 2.0; }, 1.5, moved);
  ASSERT_EQ(moved, 58 * 58);
  const QualityMeasure quality(b.vertices, b.triangles, b.labels);
  ASSERT_GT(quality.measure(crushed).flipped_faces, moved);
  const UntangledCharts u =
      untangle_flat_charts(b.vertices, crushed, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, {},
                           UntangleMinimiser::newton, {}, {}, UntangleStart::local_only);
  EXPECT_TRUE(u.untangled);
  EXPECT_EQ(u.rounds, u.local_rounds);
  EXPECT_TRUE(flat(u.positions, b));
  const Figures after = quality.measure(u.positions);
  EXPECT_EQ(after.flipped_faces, 0);
  EXPECT_EQ(after.collapsed_faces, 0);
  // Newton alone: 7 factorisations of the round's 105,800 triangles (4.2
  // s); after L-BFGS's 82 iterations, one (1.7 s).
  EXPECT_LE(u.factorizations, 3);
}

// A stop asked for during a round is seen inside its L-BFGS iterations, not
// once the round is over (at a million triangles, seconds later): the
// block above, stopped after the first poll, ends refused before L-BFGS's
// first iteration and without a factorisation (the round whole: 82
// iterations, then Newton's).
TEST(UntangleFlatCharts, StopsInsideARound) {
  const Block b = block(230, 230, 1);
  int moved = 0;
  const Vertices crushed = top_moved(
      b, 1.0, [](double x, double y) { return std::fmod(x, 4.0) == 2.0 && std::fmod(y, 4.0) == 2.0; }, 1.5, moved);
  int polls = 0;
  const UntangledCharts u =
      untangle_flat_charts(b.vertices, crushed, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, {},
                           UntangleMinimiser::newton, [&polls] { return ++polls > 1; }, {}, UntangleStart::local_only);
  EXPECT_TRUE(u.stopped);
  EXPECT_TRUE(u.refused);
  EXPECT_FALSE(u.untangled);
  EXPECT_EQ(u.iterations, 0);
  EXPECT_EQ(u.factorizations, 0);
}

TEST(UntangleFlatCharts, StopsOnceTheCollapsesPassTheCallersBound) {
  // The block with a triangle facing the wrong way (above): it ends on a
  // line. Bounded at no triangle on a line, the rounds stop when it is put
  // there, refused, after fewer rounds; bounded at what it collapses in
  // the end, nothing changes.
  Block b = block();
  const auto relabelled = std::find(b.labels.begin(), b.labels.end(), 1);
  ASSERT_NE(relabelled, b.labels.end());
  *relabelled = 0;
  const UntangledCharts unbounded = untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels);
  ASSERT_GT(unbounded.put_on_a_line, 0);
  ASSERT_FALSE(unbounded.refused);
  CollapseBound none;
  none.triangles = 0;
  const UntangledCharts refused =
      untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, none);
  EXPECT_TRUE(refused.refused);
  EXPECT_FALSE(refused.untangled);
  EXPECT_LT(refused.rounds, unbounded.rounds);
  CollapseBound area;
  area.area = 1e-6;  // the triangle's share of the area is larger
  EXPECT_TRUE(
      untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, area)
          .refused);
  CollapseBound enough;
  // As many as the unbounded result collapses (those put on a line and any
  // their shared unknowns put on a line with them).
  enough.triangles = QualityMeasure(b.vertices, b.triangles, b.labels).measure(unbounded.positions).collapsed_faces;
  const UntangledCharts same =
      untangle_flat_charts(b.vertices, b.vertices, b.triangles, b.labels, kUntangleRounds, kUntangleLocalShare, enough);
  EXPECT_FALSE(same.refused);
  EXPECT_EQ(same.rounds, unbounded.rounds);
  EXPECT_EQ(same.positions, unbounded.positions);
}

}  // namespace
}  // namespace polycube
