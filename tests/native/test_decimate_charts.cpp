#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <map>
#include <set>

#include "labels/axis.h"
#include "labels/nearest_labels.h"
#include "mesh/decimate_charts.h"
#include "mesh/triangulate.h"
#include "mesh/union_find.h"
#include "refine/refine.h"
#include "test_meshes.h"

namespace {

using namespace polycube;

struct LabelledTriangles {
  Vertices vertices;
  Triangles triangles;
  std::vector<int> labels;
};

PolygonMesh as_polygons(const Vertices& vertices, const Triangles& triangles) {
  PolygonMesh mesh;
  mesh.vertices = vertices;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    mesh.faces.add({triangles(t, 0), triangles(t, 1), triangles(t, 2)});
  return mesh;
}

Triangles as_triangles(const PolygonFaces& faces) {
  Triangles triangles(faces.count(), 3);
  for (int f = 0; f < faces.count(); ++f)
    for (int k = 0; k < 3; ++k) triangles(f, k) = faces.indices[faces.offsets[f] + k];
  return triangles;
}

LabelledTriangles refined_voxels(const std::set<std::array<int, 3>>& voxels, int levels,
                                 Triangles* unrefined = nullptr) {
  const auto surface = test_meshes::voxel_surface(voxels);
  const Triangulation split = triangulate(surface.mesh.vertices, surface.mesh.faces);
  if (unrefined) *unrefined = split.triangles;
  const Refined refined =
      refine(as_polygons(surface.mesh.vertices, split.triangles), {}, levels, RefineScheme::kBilinear);
  return {refined.mesh.vertices, as_triangles(refined.mesh.faces), nearest_labels(refined.mesh)};
}

// An L of five voxels, two high: planar charts, straight seams, concave corners.
LabelledTriangles refined_l_block(int levels, Triangles* unrefined = nullptr) {
  std::set<std::array<int, 3>> voxels;
  test_meshes::add_block(voxels, {0, 0, 0}, 3, 1, 2);
  test_meshes::add_block(voxels, {0, 1, 0}, 1, 2, 2);
  return refined_voxels(voxels, levels, unrefined);
}

LabelledTriangles triangulated_sphere(int segments, int rings) {
  const PolygonMesh sphere = test_meshes::uv_sphere(segments, rings);
  const Triangulation split = triangulate(sphere.vertices, sphere.faces);
  return {sphere.vertices, split.triangles, nearest_labels(as_polygons(sphere.vertices, split.triangles))};
}

double diagonal(const Vertices& v) { return (v.colwise().maxCoeff() - v.colwise().minCoeff()).norm(); }

// Edges as (lower, higher) vertex with the triangles on them.
std::map<std::pair<int, int>, std::vector<int>> edge_triangles(const Triangles& triangles) {
  std::map<std::pair<int, int>, std::vector<int>> edges;
  for (int t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(t, k), b = triangles(t, (k + 1) % 3);
      edges[{std::min(a, b), std::max(a, b)}].push_back(t);
    }
  return edges;
}

// Connected components of equal-label triangles across edges of two triangles.
int chart_count(const Triangles& triangles, const std::vector<int>& labels) {
  UnionFind sets(static_cast<int>(triangles.rows()));
  int count = static_cast<int>(triangles.rows());
  for (const auto& [edge, around] : edge_triangles(triangles))
    if (around.size() == 2 && labels[around[0]] == labels[around[1]] && sets.join(around[0], around[1])) --count;
  return count;
}

Vertices kept_positions(const Decimation& d, const Vertices& fine) {
  Vertices coarse(static_cast<Eigen::Index>(d.kept.size()), 3);
  for (size_t i = 0; i < d.kept.size(); ++i) coarse.row(i) = fine.row(d.kept[i]);
  return coarse;
}

// Fine triangle corners whose home is not on the coarse chart of that
// triangle: inside one of its coarse triangles, on an edge of one, or at a
// corner of one. Zero is what keeps every fine chart as flat as the coarse.
int corners_off_their_chart(const Decimation& d, const Triangles& fine) {
  std::vector<std::set<int>> charts_at_vertex(d.kept.size());
  std::map<std::pair<int, int>, std::set<int>> charts_at_edge;
  for (int t = 0; t < d.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = d.triangles(t, k), b = d.triangles(t, (k + 1) % 3);
      charts_at_vertex[a].insert(d.charts[t]);
      charts_at_edge[{std::min(a, b), std::max(a, b)}].insert(d.charts[t]);
    }
  int off = 0;
  for (int t = 0; t < fine.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int p = fine(t, k), home = d.home[p], chart = d.fine_charts[t];
      std::vector<int> support;
      for (int j = 0; j < 3; ++j)
        if (d.barycentric(p, j) != 0.0) support.push_back(d.triangles(home, j));
      bool on_chart = false;
      if (support.size() == 3) on_chart = d.charts[home] == chart;
      if (support.size() == 2)
        on_chart = charts_at_edge[{std::min(support[0], support[1]), std::max(support[0], support[1])}].count(chart);
      if (support.size() == 1) on_chart = charts_at_vertex[support[0]].count(chart);
      if (!on_chart) ++off;
    }
  return off;
}

Eigen::Vector3d normal(const Vertices& v, const Triangles& t, int f) {
  const Eigen::Vector3d a = v.row(t(f, 0)), b = v.row(t(f, 1)), c = v.row(t(f, 2));
  return (b - a).cross(c - a);
}

TEST(DecimateCharts, PlanarChartsShrinkToTheirCornersAndCarryBackExactly) {
  Triangles unrefined;
  const LabelledTriangles fine = refined_l_block(3, &unrefined);
  ASSERT_EQ(fine.triangles.rows(), 64 * unrefined.rows());
  const Decimation d = decimate_charts(fine.vertices, fine.triangles, fine.labels, 1);
  EXPECT_LE(d.triangles.rows(), 2 * unrefined.rows());

  std::map<int, int> label_of_chart;
  for (size_t t = 0; t < fine.labels.size(); ++t) label_of_chart[d.fine_charts[t]] = fine.labels[t];
  for (int t = 0; t < d.triangles.rows(); ++t) EXPECT_EQ(d.labels[t], label_of_chart.at(d.charts[t]));
  EXPECT_EQ(chart_count(d.triangles, d.labels), chart_count(fine.triangles, fine.labels));

  EXPECT_EQ(corners_off_their_chart(d, fine.triangles), 0);
  const Vertices coarse = kept_positions(d, fine.vertices);
  const double scale = diagonal(fine.vertices);
  EXPECT_LT((carry_to_fine(d, coarse) - fine.vertices).rowwise().norm().maxCoeff(), 1e-12 * scale);
  for (int t = 0; t < d.triangles.rows(); ++t) {
    const Eigen::Vector3d n = normal(coarse, d.triangles, t);
    ASSERT_GT(n.norm(), 0.0);
    EXPECT_GT(n.normalized().dot(label_axis(d.labels[t])), 1 - 1e-9) << "coarse triangle " << t;
  }
}

// What coarse to fine relies on: any polycube of the coarse mesh, carried
// back, leaves every fine chart flat. A polycube scaled per axis is one.
TEST(DecimateCharts, CarryingAMovedPolycubeKeepsEveryFineChartFlat) {
  const LabelledTriangles fine = refined_l_block(3);
  const Decimation d = decimate_charts(fine.vertices, fine.triangles, fine.labels, 1);
  const Vertices moved = kept_positions(d, fine.vertices) * Eigen::Vector3d(2, 3, 0.5).asDiagonal();
  const Vertices carried = carry_to_fine(d, moved);
  const double tolerance = 1e-12 * diagonal(moved);
  for (int t = 0; t < fine.triangles.rows(); ++t) {
    const int axis = fine.labels[t] / 2;
    const double first = carried(fine.triangles(t, 0), axis);
    for (int k = 1; k < 3; ++k) EXPECT_NEAR(carried(fine.triangles(t, k), axis), first, tolerance);
  }
}

TEST(DecimateCharts, CurvedChartsKeepTopologyChartsAndHomes) {
  const LabelledTriangles fine = triangulated_sphere(100, 100);
  ASSERT_GT(fine.triangles.rows(), 19000);
  const Decimation d = decimate_charts(fine.vertices, fine.triangles, fine.labels, 2000);
  // Half-edge collapses remove two triangles at a time; the target is met
  // unless the rules stop short of it, which they do not on a sphere.
  EXPECT_LE(d.triangles.rows(), 2000);
  EXPECT_GT(d.triangles.rows(), 1900);

  EXPECT_EQ(chart_count(d.triangles, d.labels), chart_count(fine.triangles, fine.labels));
  const long edges = static_cast<long>(edge_triangles(d.triangles).size());
  EXPECT_EQ(static_cast<long>(d.kept.size()) - edges + d.triangles.rows(), 2);

  const Vertices coarse = kept_positions(d, fine.vertices);
  for (int t = 0; t < d.triangles.rows(); ++t)
    EXPECT_GE(normal(coarse, d.triangles, t).dot(label_axis(d.labels[t])), 0.0) << "coarse triangle " << t;

  std::vector<std::set<int>> charts_of_vertex(fine.vertices.rows());
  for (int t = 0; t < fine.triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) charts_of_vertex[fine.triangles(t, k)].insert(d.fine_charts[t]);
  for (int p = 0; p < fine.vertices.rows(); ++p) {
    ASSERT_GE(d.home[p], 0);
    EXPECT_TRUE(charts_of_vertex[p].count(d.charts[d.home[p]])) << "fine vertex " << p;
  }
  EXPECT_EQ(corners_off_their_chart(d, fine.triangles), 0);
  for (int t = 0; t < fine.triangles.rows(); ++t) {
    ASSERT_GE(d.face_home[t], 0);
    ASSERT_LT(d.face_home[t], d.triangles.rows());
  }
  EXPECT_LT((carry_to_fine(d, coarse) - fine.vertices).rowwise().norm().maxCoeff(),
            0.05 * diagonal(fine.vertices));
}

// Two cubes sharing only an edge: the four faces on it are no surface, so
// that edge's vertices stay, and the rest coarsens as usual.
TEST(DecimateCharts, NonManifoldPartsStayAndTheRestCoarsens) {
  const LabelledTriangles fine = refined_voxels({{0, 0, 0}, {1, 1, 0}}, 2);
  const Decimation d = decimate_charts(fine.vertices, fine.triangles, fine.labels, 1);
  EXPECT_LT(d.triangles.rows(), fine.triangles.rows() / 4);
  for (int k = 0; k < 3; ++k) {
    const Eigen::RowVector3d on_shared_edge(1, 1, 0.25 * k);
    EXPECT_TRUE(std::any_of(d.kept.begin(), d.kept.end(), [&](int v) {
      return (fine.vertices.row(v) - on_shared_edge).norm() < 1e-12;
    })) << "shared edge point " << on_shared_edge;
  }
  EXPECT_EQ(corners_off_their_chart(d, fine.triangles), 0);
  EXPECT_LT((carry_to_fine(d, kept_positions(d, fine.vertices)) - fine.vertices).rowwise().norm().maxCoeff(),
            1e-12 * diagonal(fine.vertices));
}

TEST(DecimateCharts, RejectsBadLabelsAndTargets) {
  const LabelledTriangles fine = refined_l_block(1);
  std::vector<int> short_labels(fine.labels.begin(), fine.labels.end() - 1);
  EXPECT_THROW(decimate_charts(fine.vertices, fine.triangles, short_labels, 10), Error);
  std::vector<int> bad_label = fine.labels;
  bad_label[3] = 7;
  EXPECT_THROW(decimate_charts(fine.vertices, fine.triangles, bad_label, 10), Error);
  EXPECT_THROW(decimate_charts(fine.vertices, fine.triangles, fine.labels, 0), Error);
}

}  // namespace
