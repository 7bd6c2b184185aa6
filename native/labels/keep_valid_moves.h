// Of a set of label moves, those that break no polycube condition: each
// changed face, in order, keeps its new label when that does not raise the
// violation score (violation_score.h) above the starting labels' own, with
// the moves kept before it in place.
//
// Why: stage 8 (docs/design.md section 2.6) moves chart boundaries past the
// faces a polycube collapsed. Where the whole move breaks the conditions (a
// corner of four charts), the labeller's repair can mend it, but it mends by
// relabelling more faces, sometimes whole bands turned to the opposite
// label; keeping the moves that break nothing instead opens the anchor's
// polycube step by step (its tube's side walls, flattened to nothing, come
// back: 3.05% of the area collapsed, then 0.03%).
//
// Inputs:
//   adjacency       mesh_adjacency of the faces
//   edges_of_face   face_edges(adjacency) (violation_score.h)
//   labels          per face, 0..5: the starting labels
//   moved           per face, 0..5: labels that differ from `labels` only on `changed`
//   changed         the faces to try, in the order tried
// Returns `labels` with the kept moves applied; `kept` (when not null)
// receives how many there are.
#pragma once

#include <vector>

#include "mesh/mesh_adjacency.h"

namespace polycube {

std::vector<int> keep_valid_moves(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& edges_of_face,
                                  const std::vector<int>& labels, const std::vector<int>& moved,
                                  const std::vector<int>& changed, int* kept = nullptr);

}  // namespace polycube
