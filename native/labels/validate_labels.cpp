#include "labels/validate_labels.h"

#include <algorithm>

#include "labels/axis.h"
#include "labels/realisability.h"
#include "mesh/check_input.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"

namespace polycube {

const char* violation_kind_name(ViolationKind kind) {
  switch (kind) {
    case ViolationKind::kTooFewNeighbours: return "too_few_neighbours";
    case ViolationKind::kOppositeNeighbours: return "opposite_neighbours";
    case ViolationKind::kCornerTooManyCharts: return "corner_too_many_charts";
    case ViolationKind::kReversedChart: return "reversed_chart";
    case ViolationKind::kTurningPoint: return "turning_point";
    case ViolationKind::kSqueezedFaces: return "squeezed_faces";
  }
  return "unknown";
}

std::vector<int> filled_labels(const PolygonMesh& mesh, const std::vector<int>& labels, int* unlabelled) {
  std::vector<int> filled = labels;
  int count = 0;
  for (int f = 0; f < static_cast<int>(filled.size()); ++f)
    if (filled[f] == kUnlabelled) {
      filled[f] = nearest_axis(newell_normal(mesh.vertices, mesh.faces, f));
      ++count;
    }
  if (unlabelled) *unlabelled = count;
  return filled;
}

namespace {

void sort_unique(std::vector<int>& values) {
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
}

}  // namespace

LabelValidation validate_labels(const MeshAdjacency& adjacency, const Charts& charts, int vertex_count) {
  LabelValidation result;
  result.charts = charts.count();
  const std::vector<ChartBoundary> boundaries = chart_boundaries(adjacency, charts);
  result.boundaries = static_cast<int>(boundaries.size());

  std::vector<std::vector<int>> neighbours(charts.count());
  for (const ChartBoundary& b : boundaries) {
    neighbours[b.charts[0]].push_back(b.charts[1]);
    neighbours[b.charts[1]].push_back(b.charts[0]);
  }
  // Too few neighbours; the faces are the whole chart (it has to change as a
  // whole). Not on charts with an open side (charts_with_open_side).
  std::vector<std::vector<int>> faces_of_chart;
  const std::vector<char> open_side = charts_with_open_side(adjacency, charts);
  for (int c = 0; c < charts.count(); ++c) {
    if (neighbours[c].size() >= 4 || open_side[c]) continue;
    if (faces_of_chart.empty()) faces_of_chart = chart_faces(charts);
    LabelViolation v{ViolationKind::kTooFewNeighbours, c, charts.label[c], neighbours[c], -1, faces_of_chart[c]};
    std::sort(v.others.begin(), v.others.end());
    result.violations.push_back(std::move(v));
  }
  // Opposite labels differ only in the lowest bit (0/1, 2/3, 4/5).
  for (const ChartBoundary& b : boundaries) {
    const int a = b.charts[0], c = b.charts[1];
    if ((charts.label[a] ^ 1) != charts.label[c]) continue;
    const int smaller = charts.faces[c] < charts.faces[a] ? c : a, other = smaller == a ? c : a;
    LabelViolation v{ViolationKind::kOppositeNeighbours, smaller, charts.label[smaller], {other}, -1, {}};
    for (int e : b.edges)
      for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k) {
        const int f = adjacency.edge_faces[k];
        if (charts.of_face[f] == a || charts.of_face[f] == c) v.faces.push_back(f);
      }
    sort_unique(v.faces);
    result.violations.push_back(std::move(v));
  }
  for (int vertex = 0; vertex < vertex_count; ++vertex) {
    std::vector<int> around = charts_at_vertex(adjacency, charts, vertex);
    if (around.size() < 3) continue;
    ++result.corners;
    if (around.size() == 3) continue;
    LabelViolation v{ViolationKind::kCornerTooManyCharts, around[0], charts.label[around[0]],
                     std::vector<int>(around.begin() + 1, around.end()), vertex, {}};
    for (int k = adjacency.vertex_offsets[vertex]; k < adjacency.vertex_offsets[vertex + 1]; ++k)
      v.faces.push_back(adjacency.vertex_faces[k]);
    sort_unique(v.faces);
    result.violations.push_back(std::move(v));
  }
  return result;
}

LabelValidation validate_labels(const PolygonMesh& input, const std::vector<int>& labels) {
  const UnitBoxMesh unit(input);  // scale independence (unit_box.h)
  const PolygonMesh& mesh = unit.mesh();
  check_input(mesh, &labels);
  int unlabelled = 0;
  const std::vector<int> filled = filled_labels(mesh, labels, &unlabelled);
  const int vertex_count = static_cast<int>(mesh.vertices.rows());
  const MeshAdjacency adjacency = mesh_adjacency(mesh.faces, vertex_count);
  const Charts chart_set = charts(adjacency, filled);
  LabelValidation result = validate_labels(adjacency, chart_set, vertex_count);
  check_realisability(mesh, adjacency, chart_set, filled, result.violations);
  result.unlabelled_faces = unlabelled;
  return result;
}

}  // namespace polycube
