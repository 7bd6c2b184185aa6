// Moving chart boundaries past the faces a flat-chart solve turns over
// (flatten_charts.h).
//
// The flat solve turns over slivers where a chart boundary turns back along
// its polycube edge (docs/design.md section 3.5): the boundary's vertices
// all lie on one line, so a face whose corners come in the wrong order along
// it ends up upside down. Collapsing such a face (what flatten_charts does)
// costs its area; giving it the label of the chart across the boundary moves
// the boundary by one face and often straightens it. Measured by the caller:
// the move is kept only when the flat charts then collapse less.
//
// Inputs:
//   triangulation  the polygons' triangles
//   neighbours     face_neighbours (mesh_adjacency.h)
//   flipped        per triangle, 1 when turned over
// In/out:
//   labels         per polygon face, 0..5; every polygon with a flipped
//                  triangle takes the label most of its edge neighbours of
//                  another, not opposite, label have (ties: the lowest)
// Returns the number of faces relabelled; all moves are decided from the
// labels as given, so the result does not depend on the order of faces.
#pragma once

#include <vector>

#include "mesh/triangulate.h"

namespace polycube {

int move_boundaries_past(const Triangulation& triangulation, const std::vector<std::vector<int>>& neighbours,
                         const std::vector<char>& flipped, std::vector<int>& labels);

}  // namespace polycube
