#include "labels/realisability.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "labels/axis.h"
#include "labels/squeezed_triangles.h"
#include "mesh/triangulate.h"

namespace polycube {
namespace {

void sort_unique(std::vector<int>& values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

}  // namespace

void check_realisability(const PolygonMesh& mesh, const MeshAdjacency& adjacency, const Charts& charts,
                         const std::vector<int>& labels, std::vector<LabelViolation>& violations) {
  const std::vector<std::vector<int>> faces_of_chart = chart_faces(charts);

  // Reversed charts: the sum of Newell normals is twice the area-weighted mean normal.
  for (int c = 0; c < charts.count(); ++c) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (int f : faces_of_chart[c]) sum += newell_normal(mesh.vertices, mesh.faces, f);
    if (sum.dot(label_axis(charts.label[c])) < 0.0)
      violations.push_back({ViolationKind::kReversedChart, c, charts.label[c], {}, -1, faces_of_chart[c]});
  }

  // Turning points, boundary by boundary; each edge's direction as the first
  // chart's face walks it, so a monotone boundary has one sign along the axis.
  for (const ChartBoundary& b : chart_boundaries(adjacency, charts)) {
    const int a = b.charts[0], other = b.charts[1];
    const int axis_a = charts.label[a] / 2, axis_b = charts.label[other] / 2;
    if (axis_a == axis_b) continue;  // opposite labels: validate_labels reports them
    const int along = 3 - axis_a - axis_b;
    double forward = 0.0, backward = 0.0;
    std::vector<int> backward_edges, forward_edges;
    for (int e : b.edges) {
      for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k) {
        if (charts.of_face[adjacency.edge_faces[k]] != a) continue;
        const double step = (mesh.vertices(adjacency.edges[e][1], along) - mesh.vertices(adjacency.edges[e][0], along)) *
                            (adjacency.edge_forward[k] ? 1.0 : -1.0);
        if (step >= 0.0) {
          forward += step;
          forward_edges.push_back(e);
        } else {
          backward -= step;
          backward_edges.push_back(e);
        }
        break;
      }
    }
    if (!(std::min(forward, backward) > kTurningShare * (forward + backward))) continue;
    // The faces of the minority direction: where the boundary doubles back.
    const std::vector<int>& minority = backward < forward ? backward_edges : forward_edges;
    const int smaller = charts.faces[other] < charts.faces[a] ? other : a;
    LabelViolation v{ViolationKind::kTurningPoint, smaller, charts.label[smaller], {smaller == a ? other : a}, -1, {}};
    for (int e : minority)
      for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k) {
        const int chart = charts.of_face[adjacency.edge_faces[k]];
        if (chart == a || chart == other) v.faces.push_back(adjacency.edge_faces[k]);
      }
    sort_unique(v.faces);
    violations.push_back(std::move(v));
  }

  // Squeezed faces, one violation per chart.
  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  std::vector<int> triangle_labels(triangulation.triangles.rows());
  for (size_t t = 0; t < triangle_labels.size(); ++t) triangle_labels[t] = labels[triangulation.face_of_triangle[t]];
  const std::vector<char> squeezed = squeezed_triangles(static_cast<int>(mesh.vertices.rows()),
                                                        triangulation.triangles, triangle_labels);
  std::vector<std::vector<int>> squeezed_faces(charts.count());
  for (size_t t = 0; t < squeezed.size(); ++t)
    if (squeezed[t]) {
      const int f = triangulation.face_of_triangle[t];
      squeezed_faces[charts.of_face[f]].push_back(f);
    }
  for (int c = 0; c < charts.count(); ++c) {
    if (squeezed_faces[c].empty()) continue;
    sort_unique(squeezed_faces[c]);
    violations.push_back({ViolationKind::kSqueezedFaces, c, charts.label[c], {}, -1, std::move(squeezed_faces[c])});
  }
}

}  // namespace polycube
