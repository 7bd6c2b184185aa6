// Checks a labeling against the polycube conditions of DESIGN.md section 3
// (Eppstein-Mumford, as quoted by Zhao et al.): every chart touches at least
// four other charts, no two adjacent charts have opposite labels, and every
// corner (a vertex where three or more charts meet) joins exactly three.
// Every violation is listed with the faces involved, so a user can find it;
// the deformation itself still runs on an invalid labeling.
#pragma once

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
};

// "too_few_neighbours", "opposite_neighbours", "corner_too_many_charts": the
// names in reports, JSON and the Python dicts.
const char* violation_kind_name(ViolationKind kind);

struct LabelViolation {
  ViolationKind kind;
  int chart = -1;           // the chart at fault: the smaller one of an opposite pair, the
                            // smallest chart at a corner
  int label = -1;           // its label
  std::vector<int> others;  // its neighbours (too few), the opposite chart, or the other
                            // charts at the corner
  int vertex = -1;          // the corner's vertex; -1 for the other kinds
  std::vector<int> faces;   // the faces to look at, increasing: the whole chart (too few),
                            // the faces along the shared boundary on both sides (opposite),
                            // the faces around the vertex (corner)
};

struct LabelValidation {
  int charts = 0;
  int boundaries = 0;        // pairs of charts sharing at least one edge
  int corners = 0;           // vertices where three or more charts meet
  int unlabelled_faces = 0;  // given as -1 and judged with their nearest axis, as deform() does
  std::vector<LabelViolation> violations;  // too few, then opposite, then corners; by chart/vertex

  bool valid() const { return violations.empty(); }
};

// labels: one per face, -1..5; -1 takes the nearest axis of the face normal.
// Throws Error on input check_input rejects.
LabelValidation validate_labels(const PolygonMesh& mesh, const std::vector<int>& labels);

// The same on a labeling without -1, with the adjacency and charts already
// built (the automatic labeller validates many candidate labelings).
LabelValidation validate_labels(const MeshAdjacency& adjacency, const Charts& charts, int vertex_count);

// The labels with every -1 replaced by the nearest axis of its face normal:
// the labels deform() uses. unlabelled, when given, gets how many there were.
std::vector<int> filled_labels(const PolygonMesh& mesh, const std::vector<int>& labels, int* unlabelled = nullptr);

}  // namespace polycube
