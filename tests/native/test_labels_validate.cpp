// The validator (docs/design.md sections 3.2 and 3.5) on labelings whose
// violations are worked out by hand, and the orientation check.
#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <random>

#include "io/labels_io.h"
#include "io/read_mesh.h"
#include "labels/axis.h"
#include "labels/keep_valid_moves.h"
#include "labels/nearest_labels.h"
#include "labels/orientation.h"
#include "labels/validate_labels.h"
#include "labels/violation_score.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"
#include "test_meshes.h"

namespace {

using namespace polycube;
using test_meshes::LabelledMesh;

// A 6x6x6 box of unit quads with its exact labels: 6 charts, 12 boundaries, 8 corners.
LabelledMesh box6() {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 6, 6, 6);
  return test_meshes::voxel_surface(voxels);
}

Eigen::Vector3d centroid(const PolygonMesh& mesh, int f) {
  Eigen::Vector3d c = Eigen::Vector3d::Zero();
  for (int k = mesh.faces.offsets[f]; k < mesh.faces.offsets[f + 1]; ++k)
    c += mesh.vertices.row(mesh.faces.indices[k]).transpose();
  return c / mesh.faces.size(f);
}

// Faces with the given label whose centroid passes `where`.
template <class Where>
std::vector<int> faces_where(const LabelledMesh& m, int label, Where where) {
  std::vector<int> faces;
  for (int f = 0; f < m.mesh.faces.count(); ++f)
    if (m.labels[f] == label && where(centroid(m.mesh, f))) faces.push_back(f);
  return faces;
}

void relabel(LabelledMesh& m, const std::vector<int>& faces, int label) {
  for (int f : faces) m.labels[f] = label;
}

int vertex_at(const PolygonMesh& mesh, Eigen::Vector3d p) {
  for (int v = 0; v < mesh.vertices.rows(); ++v)
    if ((mesh.vertices.row(v).transpose() - p).norm() < 1e-9) return v;
  return -1;
}

constexpr int kPX = 0, kPY = 2, kPZ = 4, kNZ = 5;

int count_kind(const LabelValidation& v, ViolationKind kind) {
  return static_cast<int>(
      std::count_if(v.violations.begin(), v.violations.end(), [&](const LabelViolation& x) { return x.kind == kind; }));
}

// The polycube conditions' violations, which come first in the list.
size_t topological(const LabelValidation& v) {
  return static_cast<size_t>(count_kind(v, ViolationKind::kTooFewNeighbours) +
                             count_kind(v, ViolationKind::kOppositeNeighbours) +
                             count_kind(v, ViolationKind::kCornerTooManyCharts));
}

TEST(ValidateLabels, ExactBoxIsValid) {
  const LabelledMesh box = box6();
  const LabelValidation v = validate_labels(box.mesh, box.labels);
  EXPECT_TRUE(v.valid());
  EXPECT_EQ(v.charts, 6);
  EXPECT_EQ(v.boundaries, 12);
  EXPECT_EQ(v.corners, 8);
  EXPECT_EQ(v.unlabelled_faces, 0);
}

TEST(ValidateLabels, UnlabelledFacesAreJudgedByTheirNearestAxis) {
  const LabelledMesh box = box6();
  const LabelValidation v = validate_labels(box.mesh, std::vector<int>(box.labels.size(), kUnlabelled));
  EXPECT_TRUE(v.valid());
  EXPECT_EQ(v.charts, 6);
  EXPECT_EQ(v.unlabelled_faces, box.mesh.faces.count());
}

// The top split in halves, +Z and -Z: each half still touches four charts and
// every corner joins three, so the one violation is the opposite pair.
TEST(ValidateLabels, OppositeChartsSideBySide) {
  LabelledMesh box = box6();
  relabel(box, faces_where(box, kPZ, [](auto c) { return c.x() > 3; }), kNZ);
  const LabelValidation v = validate_labels(box.mesh, box.labels);
  ASSERT_EQ(topological(v), 1u);
  EXPECT_EQ(count_kind(v, ViolationKind::kReversedChart), 1);  // the -Z half faces up
  const LabelViolation& o = v.violations[0];
  EXPECT_EQ(o.kind, ViolationKind::kOppositeNeighbours);
  EXPECT_EQ(o.others.size(), 1u);
  EXPECT_TRUE(o.label == kPZ || o.label == kNZ);
  std::vector<int> along = faces_where(box, kPZ, [](auto c) { return c.x() > 2 && c.x() < 3; });
  for (int f : faces_where(box, kNZ, [](auto c) { return c.z() > 5 && c.x() > 3 && c.x() < 4; })) along.push_back(f);
  std::sort(along.begin(), along.end());
  EXPECT_EQ(o.faces, along);
  EXPECT_EQ(v.charts, 7);
  EXPECT_EQ(v.corners, 10);
}

// One top corner quad labelled -Z: it touches the top, +X and +Y (three
// charts), and the top is its opposite. No label for that quad avoids both.
TEST(ValidateLabels, ChartWithThreeNeighbours) {
  LabelledMesh box = box6();
  const std::vector<int> patch = faces_where(box, kPZ, [](auto c) { return c.x() > 5 && c.y() > 5; });
  ASSERT_EQ(patch.size(), 1u);
  const std::vector<int> beside =
      faces_where(box, kPZ, [](auto c) { return (c.x() > 5 && c.y() > 4) || (c.x() > 4 && c.y() > 5); });
  relabel(box, patch, kNZ);
  const LabelValidation v = validate_labels(box.mesh, box.labels);
  ASSERT_EQ(topological(v), 2u);
  EXPECT_EQ(count_kind(v, ViolationKind::kReversedChart), 1);
  EXPECT_EQ(v.violations[0].kind, ViolationKind::kTooFewNeighbours);
  EXPECT_EQ(v.violations[0].label, kNZ);
  EXPECT_EQ(v.violations[0].others.size(), 3u);
  EXPECT_EQ(v.violations[0].faces, patch);
  EXPECT_EQ(v.violations[1].kind, ViolationKind::kOppositeNeighbours);
  EXPECT_EQ(v.violations[1].chart, v.violations[0].chart);  // the smaller of the two
  EXPECT_EQ(v.violations[1].faces, beside);                 // the quad and the two top quads beside it
}

// The top in quadrants: +Z, +Y (joining the +Y side), +Z again, +X (joining
// the +X side). Four charts meet at the centre; the second +Z quadrant is then
// enclosed by +X and +Y alone.
TEST(ValidateLabels, FourChartCorner) {
  LabelledMesh box = box6();
  relabel(box, faces_where(box, kPZ, [](auto c) { return c.x() < 3 && c.y() > 3; }), kPY);
  relabel(box, faces_where(box, kPZ, [](auto c) { return c.x() > 3 && c.y() < 3; }), kPX);
  const std::vector<int> enclosed = faces_where(box, kPZ, [](auto c) { return c.x() > 3 && c.y() > 3; });
  const LabelValidation v = validate_labels(box.mesh, box.labels);
  ASSERT_EQ(topological(v), 2u);
  EXPECT_EQ(v.violations[0].kind, ViolationKind::kTooFewNeighbours);
  EXPECT_EQ(v.violations[0].faces, enclosed);
  EXPECT_EQ(v.violations[0].others.size(), 2u);
  const LabelViolation& corner = v.violations[1];
  EXPECT_EQ(corner.kind, ViolationKind::kCornerTooManyCharts);
  EXPECT_EQ(corner.vertex, vertex_at(box.mesh, {3, 3, 6}));
  EXPECT_EQ(corner.others.size(), 3u);
  EXPECT_EQ(corner.faces.size(), 4u);
}

TEST(ValidateLabels, B0PublishedLabelingIsValid) {
  const std::string dir = std::string(POLYCUBE_SHARED_DATA) + "/B0";
  if (!std::ifstream(dir + "/surface.obj").good()) GTEST_SKIP() << dir << " is missing";
  const PolygonMesh mesh = read_mesh(dir + "/surface.obj");
  const std::vector<int> labels = read_labels(dir + "/labeling.txt", mesh.faces.count());
  const LabelValidation v = validate_labels(mesh, labels);
  std::printf("  B0: %d charts, %d boundaries, %d corners, %zu violations\n", v.charts, v.boundaries, v.corners,
              v.violations.size());
  for (const LabelViolation& violation : v.violations)
    std::printf("    %s chart %d (%zu faces)\n", violation_kind_name(violation.kind), violation.chart,
                violation.faces.size());
  EXPECT_TRUE(v.valid());
  EXPECT_TRUE(v.realisable());  // no reversed chart, no turning point, nothing squeezed
  EXPECT_GE(v.charts, 6);
}

// Every +X face of B0's published labeling made -X and the other way round:
// the chart topology is untouched, but no polycube realises charts that point
// away from their axes.
TEST(ValidateLabels, RejectsChartsPointingAwayFromTheirAxes) {
  const std::string dir = std::string(POLYCUBE_SHARED_DATA) + "/B0";
  if (!std::ifstream(dir + "/surface.obj").good()) GTEST_SKIP() << dir << " is missing";
  const PolygonMesh mesh = read_mesh(dir + "/surface.obj");
  std::vector<int> labels = read_labels(dir + "/labeling.txt", mesh.faces.count());
  int x_charts = 0;
  const LabelValidation published = validate_labels(mesh, labels);
  for (int f = 0; f < mesh.faces.count(); ++f)
    if (labels[f] / 2 == 0) labels[f] ^= 1;
  const LabelValidation v = validate_labels(mesh, labels);
  EXPECT_EQ(v.charts, published.charts);
  EXPECT_FALSE(v.valid());
  for (const LabelViolation& violation : v.violations) {
    EXPECT_EQ(violation.kind, ViolationKind::kReversedChart);
    EXPECT_EQ(violation.label / 2, 0);
    ++x_charts;
  }
  EXPECT_GE(x_charts, 2);
}

// An L-shaped tongue of the +X side reaching into the top (+Z) of the box:
// along y = 1 to x = 3, then an arm up to y = 5 at x in [3, 4]. The +X/+Z
// boundary must become one edge along Y, but it climbs the arm's left side
// and comes back down its right side: 3 of its 12 units along Y go
// backwards, a turning point, reported with the faces where it turns back.
TEST(ValidateLabels, BoundaryThatDoublesBackIsATurningPoint) {
  LabelledMesh box = box6();
  relabel(box, faces_where(box, kPZ, [](const Eigen::Vector3d& c) { return c.x() > 3 && c.y() > 1 && c.y() < 2; }),
          kPX);
  relabel(
      box,
      faces_where(box, kPZ, [](const Eigen::Vector3d& c) { return c.x() > 3 && c.x() < 4 && c.y() > 2 && c.y() < 5; }),
      kPX);
  const LabelValidation v = validate_labels(box.mesh, box.labels);
  EXPECT_TRUE(v.valid());
  ASSERT_EQ(count_kind(v, ViolationKind::kTurningPoint), 1);
  EXPECT_FALSE(v.realisable());
  for (const LabelViolation& violation : v.violations) {
    if (violation.kind != ViolationKind::kTurningPoint) continue;
    for (int f : violation.faces) {  // along the arm's right side, x = 4, y in [2, 5]
      const Eigen::Vector3d c = centroid(box.mesh, f);
      EXPECT_NEAR(c.x(), 4.0, 0.5 + 1e-9);
      EXPECT_GT(c.y(), 2.0);
    }
  }
}

// A +Y face whose three corners lie on the top (+Z) plane: the top chart and
// the box's other charts leave it no height, so flat charts squeeze it.
TEST(ValidateLabels, FaceWithAllCornersOnAnotherChartsPlaneIsSqueezed) {
  LabelledMesh box = box6();
  EXPECT_EQ(count_kind(validate_labels(box.mesh, box.labels), ViolationKind::kSqueezedFaces), 0);
  // A single top face in the middle of the top chart, labelled +Y: every corner is on the +Z plane.
  const std::vector<int> middle =
      faces_where(box, kPZ, [](const Eigen::Vector3d& c) { return c.x() > 2 && c.x() < 3 && c.y() > 2 && c.y() < 3; });
  ASSERT_EQ(middle.size(), 1u);
  relabel(box, middle, kPY);
  const LabelValidation v = validate_labels(box.mesh, box.labels);
  ASSERT_EQ(count_kind(v, ViolationKind::kSqueezedFaces), 1);
  for (const LabelViolation& violation : v.violations) {
    if (violation.kind == ViolationKind::kSqueezedFaces) {
      EXPECT_EQ(violation.faces, middle);
    }
  }
}

// A box without its top: each side touches the bottom and two sides, and
// its open side is where the fourth neighbour would be. The four-neighbour
// rule is for closed surfaces (docs/design.md section 3.2); the other rules
// still hold on an open mesh.
TEST(ValidateLabels, ChartsWithAnOpenSideNeedNoFourthNeighbour) {
  const LabelledMesh box = box6();
  LabelledMesh open;
  open.mesh.vertices = box.mesh.vertices;
  for (int f = 0; f < box.mesh.faces.count(); ++f) {
    if (box.labels[f] == kPZ) continue;
    const int* corner = &box.mesh.faces.indices[box.mesh.faces.offsets[f]];
    open.mesh.faces.add({corner[0], corner[1], corner[2], corner[3]});
    open.labels.push_back(box.labels[f]);
  }
  const LabelValidation v = validate_labels(open.mesh, open.labels);
  EXPECT_TRUE(v.valid());
  EXPECT_EQ(topological(v), 0u);
  EXPECT_EQ(v.charts, 5);
  // A closed chart on it is still held to four: one bottom corner quad
  // labelled +Z touches the bottom and two sides only.
  const std::vector<int> patch = faces_where(open, kNZ, [](auto c) { return c.x() > 5 && c.y() > 5; });
  ASSERT_EQ(patch.size(), 1u);
  relabel(open, patch, kPZ);
  EXPECT_EQ(count_kind(validate_labels(open.mesh, open.labels), ViolationKind::kTooFewNeighbours), 1);
}

TEST(ValidateLabels, RejectsBadLabels) {
  const LabelledMesh box = box6();
  std::vector<int> labels = box.labels;
  labels[3] = 6;
  EXPECT_THROW(validate_labels(box.mesh, labels), Error);
  labels.pop_back();
  EXPECT_THROW(validate_labels(box.mesh, labels), Error);
}

PolygonMesh reversed(PolygonMesh mesh) {
  for (int f = 0; f < mesh.faces.count(); ++f)
    std::reverse(mesh.faces.indices.begin() + mesh.faces.offsets[f],
                 mesh.faces.indices.begin() + mesh.faces.offsets[f + 1]);
  return mesh;
}

// A model of Debian's libcgal-demo with what the repair's counts need.
struct CountedModel {
  explicit CountedModel(const PolygonMesh& m)
      : mesh(m),
        adjacency(mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows()))),
        edges(face_edges(adjacency, mesh.faces.count())),
        neighbours(face_neighbours(adjacency, mesh.faces.count())) {}
  PolygonMesh mesh;
  MeshAdjacency adjacency;
  std::vector<std::vector<int>> edges, neighbours;
};

std::string cgal_path(const std::string& name) { return std::string(POLYCUBE_MESH_DATA) + "/" + name + ".off"; }

// The repair's incremental score (labels/violation_score.h) gives the same
// number as counting the whole mesh, for every kind of move the repair makes:
// single faces, whole charts (merging and splitting charts) and bands, on a
// closed model with many violations and on one with open sides.
TEST(ViolationDelta, EqualsTheWholeCount) {
  int checked = 0;
  for (const char* name : {"elephant", "mech-holes-shark"}) {
    const std::string path = cgal_path(name);
    if (!std::ifstream(path).good()) GTEST_SKIP() << path << " is missing: run `make data`";
    const CountedModel model(read_mesh(path));
    const MeshAdjacency& adjacency = model.adjacency;
    const std::vector<std::vector<int>>&edges = model.edges, &neighbours = model.neighbours;
    const int face_count = model.mesh.faces.count();
    std::vector<int> labels = nearest_labels(model.mesh);
    std::mt19937 random(7);
    for (int round = 0; round < 6; ++round) {
      ViolationDelta delta(adjacency, edges, labels);
      EXPECT_EQ(delta.score(), violation_score(adjacency, labels));
      const Charts ch = charts(adjacency, labels);
      const std::vector<std::vector<int>> faces_of_chart = chart_faces(ch);
      for (int trial = 0; trial < 60; ++trial) {
        const int seed = static_cast<int>(random() % face_count), label = static_cast<int>(random() % 6);
        std::vector<int> faces;
        switch (trial % 3) {
          case 0:
            faces = {seed};
            break;
          case 1:
            faces = faces_of_chart[ch.of_face[seed]];
            break;
          default:
            faces = neighbours[seed];
            faces.push_back(seed);
            for (int f : neighbours[seed]) faces.insert(faces.end(), neighbours[f].begin(), neighbours[f].end());
        }
        std::vector<int> candidate = labels;
        for (int f : faces) candidate[f] = label;
        ASSERT_EQ(delta.score_of(candidate, faces), violation_score(adjacency, candidate))
            << name << " trial " << trial;
        ++checked;
        if (trial == 59) labels = candidate;  // the next round starts from another labeling
      }
    }
  }
  EXPECT_EQ(checked, 720);
}

// Moves kept into the incremental score one after another (keep_last, as
// keep_valid_moves does) leave it exact: its score, and the score of the next
// move of every kind, equal whole counts through 300 kept moves that split,
// merge and remove charts.
TEST(ViolationDelta, StaysExactAsMovesAreKept) {
  int kept = 0;
  for (const char* name : {"elephant", "mech-holes-shark"}) {
    const std::string path = cgal_path(name);
    if (!std::ifstream(path).good()) GTEST_SKIP() << path << " is missing: run `make data`";
    const CountedModel model(read_mesh(path));
    const MeshAdjacency& adjacency = model.adjacency;
    const std::vector<std::vector<int>>& neighbours = model.neighbours;
    const int face_count = model.mesh.faces.count();
    std::vector<int> labels = nearest_labels(model.mesh);
    ViolationDelta delta(adjacency, model.edges, labels);
    std::mt19937 random(11);
    for (int trial = 0; trial < 150; ++trial) {
      const int seed = static_cast<int>(random() % face_count), label = static_cast<int>(random() % 6);
      std::vector<int> faces = {seed};
      if (trial % 3 == 1) faces = delta.faces_of_chart()[delta.charts().of_face[seed]];
      if (trial % 3 == 2) faces.insert(faces.end(), neighbours[seed].begin(), neighbours[seed].end());
      std::vector<int> candidate = labels;
      for (int f : faces) candidate[f] = label;
      ASSERT_EQ(delta.score_of(candidate, faces), violation_score(adjacency, candidate)) << name << " trial " << trial;
      delta.keep_last();
      labels = candidate;
      ASSERT_EQ(delta.score(), violation_score(adjacency, labels)) << name << " trial " << trial;
      ++kept;
    }
  }
  EXPECT_EQ(kept, 300);
}

// What keeping each move that raises no violation, tried one at a time with
// the moves kept before it in place, gives when every try is a whole count.
std::vector<int> kept_by_whole_counts(const MeshAdjacency& adjacency, const std::vector<int>& labels,
                                      const std::vector<int>& moved, const std::vector<int>& changed) {
  const int limit = violation_score(adjacency, labels);
  std::vector<int> result = labels;
  for (int f : changed) {
    result[f] = moved[f];
    if (violation_score(adjacency, result) > limit) result[f] = labels[f];
  }
  return result;
}

// The box's whole top turned +X, the row beside the +X side first, and an
// island on the bottom: the rows go over one by one until the top chart
// would vanish (+X would then meet -X); the island (one neighbour) never.
TEST(KeepValidMoves, KeepsTheMovesThatBreakNothingInTurn) {
  const LabelledMesh m = box6();
  const MeshAdjacency adjacency = mesh_adjacency(m.mesh.faces, static_cast<int>(m.mesh.vertices.rows()));
  const std::vector<std::vector<int>> edges = face_edges(adjacency, m.mesh.faces.count());
  std::vector<int> changed = faces_where(m, kPZ, [](const Eigen::Vector3d&) { return true; });
  std::stable_sort(changed.begin(), changed.end(),
                   [&](int a, int b) { return centroid(m.mesh, a).x() > centroid(m.mesh, b).x(); });
  const std::vector<int> island = faces_where(
      m, kNZ, [](const Eigen::Vector3d& c) { return std::abs(c.x() - 2.5) < 0.1 && std::abs(c.y() - 2.5) < 0.1; });
  ASSERT_EQ(island.size(), 1u);
  changed.push_back(island[0]);
  std::vector<int> moved = m.labels;
  for (int f : changed) moved[f] = kPX;
  int kept = -1;
  const std::vector<int> result = keep_valid_moves(adjacency, edges, m.labels, moved, changed, &kept);
  EXPECT_EQ(violation_score(adjacency, result), 0);
  EXPECT_EQ(result, kept_by_whole_counts(adjacency, m.labels, moved, changed));
  EXPECT_GE(kept, 30);  // five rows of six at least
  EXPECT_LT(kept, 36);  // not the whole top
  EXPECT_EQ(result[island[0]], kNZ);
}

// The same as whole counts on a real model's noisy labels, through hundreds
// of moves kept into the incremental count.
TEST(KeepValidMoves, EqualsWholeCountsOnTheElephant) {
  const std::string path = cgal_path("elephant");
  if (!std::ifstream(path).good()) GTEST_SKIP() << path << " is missing: run `make data`";
  const CountedModel model(read_mesh(path));
  const MeshAdjacency& adjacency = model.adjacency;
  const std::vector<std::vector<int>>& neighbours = model.neighbours;
  const int face_count = model.mesh.faces.count();
  const std::vector<int> labels = nearest_labels(model.mesh);
  // Faces on chart boundaries take a neighbour's label, as stage 8 moves them.
  std::vector<int> moved = labels, changed;
  for (int f = 0; f < face_count && changed.size() < 400; f += 3)
    for (int g : neighbours[f])
      if (labels[g] != labels[f] && (labels[g] ^ 1) != labels[f]) {
        moved[f] = labels[g];
        changed.push_back(f);
        break;
      }
  int kept = 0;
  const std::vector<int> result = keep_valid_moves(adjacency, model.edges, labels, moved, changed, &kept);
  EXPECT_EQ(result, kept_by_whole_counts(adjacency, labels, moved, changed));
  EXPECT_GT(kept, 64);
  EXPECT_LT(kept, static_cast<int>(changed.size()));
  EXPECT_LE(violation_score(adjacency, result), violation_score(adjacency, labels));
}

TEST(Orientation, OutwardInwardInconsistentAndNonOrientable) {
  const PolygonMesh sphere = test_meshes::uv_sphere(16, 8);
  const std::vector<int> labels = nearest_labels(sphere);
  const Orientation out = orientation(sphere, &labels);
  EXPECT_TRUE(out.orientable);
  EXPECT_TRUE(out.consistent);
  EXPECT_EQ(out.components, 1);
  EXPECT_EQ(out.closed_components, 1);
  EXPECT_FALSE(out.inward());
  EXPECT_FALSE(out.labels_opposite);
  EXPECT_LT(out.area_against_labels, 1e-12);

  // Inward copy with the outward labels: detected both ways; flipping the labels fits the winding.
  const PolygonMesh inside_out = reversed(sphere);
  const Orientation in = orientation(inside_out, &labels);
  EXPECT_TRUE(in.consistent);
  EXPECT_TRUE(in.inward());
  EXPECT_TRUE(in.labels_opposite);
  EXPECT_GT(in.area_against_labels, 0.999);
  const std::vector<int> flipped = flip_labels(labels);
  EXPECT_FALSE(orientation(inside_out, &flipped).labels_opposite);
  EXPECT_EQ(flip_labels(flipped), labels);
  EXPECT_EQ(flip_labels({-1, 0, 3, 4}), (std::vector<int>{-1, 1, 2, 5}));

  PolygonMesh one_flipped = sphere;
  std::reverse(one_flipped.faces.indices.begin() + one_flipped.faces.offsets[20],
               one_flipped.faces.indices.begin() + one_flipped.faces.offsets[21]);
  const Orientation mixed = orientation(one_flipped);
  EXPECT_TRUE(mixed.orientable);
  EXPECT_FALSE(mixed.consistent);
  EXPECT_EQ(mixed.inconsistent_edges, 4);
  EXPECT_FALSE(mixed.inward());

  const Orientation moebius = orientation(test_meshes::moebius_strip(40, 3));
  EXPECT_FALSE(moebius.orientable);
  EXPECT_FALSE(moebius.consistent);
  EXPECT_EQ(moebius.closed_components, 0);
}

}  // namespace
