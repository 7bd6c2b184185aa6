// Whether flat charts can realise a labeling without collapsing faces or
// turning the surface inside out (docs/design.md section 3.5): the checks
// beyond the topological polycube conditions of validate_labels.h.
//
// - reversed chart: the chart's area-weighted mean normal points away from
//   its label's axis (more than 90 degrees); no polycube realises it without
//   turning the surface inside out, so it makes a labeling invalid;
// - turning point: a boundary between two charts becomes one straight
//   polycube edge along the axis neither label names, so it must run
//   monotonically along that axis; a boundary that doubles back along it
//   (by more than kTurningShare of its length along the axis, measured on
//   the input) forces a staircase, which flattens only by collapsing faces;
// - squeezed faces: faces that flat charts squeeze onto a line whatever the
//   geometry (labels/squeezed_triangles.h): teeth on a zigzag boundary,
//   strips one face wide.
// Each is reported with its chart and the faces to look at.
#pragma once

#include <vector>

#include "labels/charts.h"
#include "labels/validate_labels.h"
#include "mesh/mesh.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {

// The share of a boundary's travel along its edge axis that may go backwards
// before it counts as a turning point: noise on a boundary that follows the
// axis stays well below it (B0's published labeling: under 1%).
constexpr double kTurningShare = 0.2;

// Appends the violations above for `labels` (0..5, one per face; `charts` of
// them) to `violations`.
void check_realisability(const PolygonMesh& mesh, const MeshAdjacency& adjacency, const Charts& charts,
                         const std::vector<int>& labels, std::vector<LabelViolation>& violations);

}  // namespace polycube
