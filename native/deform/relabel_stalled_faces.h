// Local label repair for the `robust` variant: faces that cannot reach their
// label's axis without folding.
//
// The fold-free step control stops a triangle from turning over, so a face
// whose label asks for a turn the neighbourhood cannot make (a face on a
// staircase chart boundary that stands perpendicular to its axis, a face of
// an input labeling that already points away from its axis) stalls there,
// typically near 90 degrees. If an adjacent face's label is closer to its
// current normal than its own, the face geometrically belongs to that chart:
// relabelling it only moves a chart boundary by one face, it creates no new
// chart, and the face then converges with its new chart. A polygon is only
// relabelled when all its triangles face the new axis (else the relabelling
// itself would show a flipped triangle). Faces with no better neighbouring
// label are left alone (and end up in the report's unconverged faces).
#pragma once

#include <vector>

#include "deform/quality.h"
#include "mesh/triangulate.h"

namespace polycube {

// `neighbours`: face_neighbours (mesh_adjacency.h). Relabels the stalled polygon faces (see above): those with a triangle that
// deviates more than `min_deviation_deg`; updates `labels` (per polygon) and returns
// the faces changed, ascending.
std::vector<int> relabel_stalled_faces(const Vertices& positions, const Triangulation& triangulation,
                                       const std::vector<std::vector<int>>& adjacency, const FaceStates& states,
                                       double min_deviation_deg, std::vector<int>& labels);

}  // namespace polycube
