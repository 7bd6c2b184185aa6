// Checks a labeling against the polycube conditions of docs/design.md
// section 3.2 (Eppstein-Mumford, as quoted by Zhao et al.): every chart
// touches at least four other charts, no two adjacent charts have opposite
// labels, and every corner (a vertex where three or more charts meet) joins
// exactly three; and, on a mesh, whether flat charts can realise it
// (labels/realisability.h: reversed charts, turning points, squeezed faces).
// Every violation is listed with the faces involved, so a user can find it;
// the deformation itself still runs on an invalid labeling.
#pragma once

#include <algorithm>
#include <string>
#include <vector>

#include "labels/charts.h"
#include "mesh/mesh.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {

enum class ViolationKind {
  kTooFewNeighbours,    // a chart touching fewer than four other charts
  kOppositeNeighbours,  // two adjacent charts with opposite labels (+X next to -X, ...)
  kCornerTooManyCharts, // a vertex where more than three charts meet
  kReversedChart,       // a chart whose mean normal points away from its axis
  kTurningPoint,        // a chart boundary that doubles back along its polycube edge
  kSqueezedFaces,       // faces flat charts must squeeze onto a line
};

// The kinds that make a labeling invalid; the others only make it
// unrealisable without collapsing faces.
inline bool makes_invalid(ViolationKind kind) {
  return kind != ViolationKind::kTurningPoint && kind != ViolationKind::kSqueezedFaces;
}

// "too_few_neighbours", "opposite_neighbours", "corner_too_many_charts",
// "reversed_chart", "turning_point", "squeezed_faces": the names in reports,
// JSON and the Python dicts.
const char* violation_kind_name(ViolationKind kind);

struct LabelViolation {
  ViolationKind kind;
  int chart = -1;           // the chart at fault: the smaller one of an opposite pair or of
                            // a boundary with a turning point, the smallest chart at a corner
  int label = -1;           // its label
  std::vector<int> others;  // its neighbours (too few), the opposite chart, the other
                            // charts at the corner, the other chart of the boundary
  int vertex = -1;          // the corner's vertex; -1 for the other kinds
  std::vector<int> faces;   // the faces to look at, increasing: the whole chart (too few,
                            // reversed), the faces along the shared boundary on both sides
                            // (opposite; turning point: where it doubles back), the faces
                            // around the vertex (corner), the squeezed faces
};

struct LabelValidation {
  int charts = 0;
  int boundaries = 0;        // pairs of charts sharing at least one edge
  int corners = 0;           // vertices where three or more charts meet
  int unlabelled_faces = 0;  // given as -1 and judged with their nearest axis, as deform() does
  // too few, opposite, corners, then (on a mesh) reversed, turning points, squeezed
  std::vector<LabelViolation> violations;

  // The polycube conditions hold and no chart is reversed.
  bool valid() const {
    return std::none_of(violations.begin(), violations.end(),
                        [](const LabelViolation& v) { return makes_invalid(v.kind); });
  }
  // Valid, and flat charts can realise it without collapsing faces.
  bool realisable() const { return violations.empty(); }
};

// labels: one per face, -1..5; -1 takes the nearest axis of the face normal.
// Checks realisability too. Throws Error on input check_input rejects.
LabelValidation validate_labels(const PolygonMesh& mesh, const std::vector<int>& labels);

// The topological conditions only, on a labeling without -1, with the
// adjacency and charts already built (the automatic labeller validates many
// candidate labelings).
LabelValidation validate_labels(const MeshAdjacency& adjacency, const Charts& charts, int vertex_count);

// The labels with every -1 replaced by the nearest axis of its face normal:
// the labels deform() uses. unlabelled, when given, gets how many there were.
std::vector<int> filled_labels(const PolygonMesh& mesh, const std::vector<int>& labels, int* unlabelled = nullptr);

}  // namespace polycube
