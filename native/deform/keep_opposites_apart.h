// Faces of opposite labels (+X beside -X) kept from touching where the
// labels are ours to change (docs/design.md section 2.6).
//
// In an exact polycube two faces of opposite labels that share an edge lie in
// one plane of their axis, facing away from each other: the edge between
// them folds unless one of the two collapses, and a run whose result folds
// more edges than its input is refused. Relabelling that moves a chart
// boundary face by face makes such pairs where two charts of opposite labels
// meet across a strip (the armadillo refined 16 times: the coarse route's
// labels carried to the fine faces made 10, and its fine run was refused).
//
// Inputs:
//   mesh        its faces' normals choose where no neighbour's label will do
//   neighbours  face_neighbours (mesh_adjacency.h)
//   given       per polygon face, 0..5: the labels before the change
// In/out:
//   labels      per polygon face, 0..5: each face whose label differs from
//               `given` and is opposite a neighbour's takes back its given
//               label when that is opposite none of its neighbours', else
//               the label most of its neighbours have among those opposite
//               none (ties: the lowest), else the label nearest its normal
//               among those opposite none, else stays. Each change removes
//               pairs and makes none, so this ends.
// Returns the faces changed, ascending.
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {

std::vector<int> keep_opposites_apart(const PolygonMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                                      const std::vector<int>& given, std::vector<int>& labels);

// The labels' own pairs: faces of opposite labels across an edge the input
// does not fold (normals at most 120 degrees apart, docs/design.md section
// 4), where any exact polycube folds the edge or collapses one of the two.
// Nearest labels make them on thin ridges (the camel: 9, refined 4 times:
// 18), and at a finer resolution the flattening no longer collapses them
// away: every untangled attempt folded 12 to 18 edges where the input has 4,
// and no run was exact (docs/design.md section 2.6, stage 9).
// Of each pair, the face whose normal is farther from its label's axis
// takes the label nearest its normal among those opposite none of its
// neighbours' (if there is none, it stays). Each change removes a pair and
// makes none, so this ends. `neighbours`: face_neighbours of `adjacency`.
// Returns the faces changed, ascending.
std::vector<int> part_opposite_neighbours(const PolygonMesh& mesh, const MeshAdjacency& adjacency,
                                          const std::vector<std::vector<int>>& neighbours, std::vector<int>& labels);

// Whether a neighbour of face `f` has the label opposite `label` (0..5).
bool touches_opposite(const std::vector<std::vector<int>>& neighbours, const std::vector<int>& labels, int f,
                      int label);

}  // namespace polycube
