// Faces whose label points away from their own normal (more than 90
// degrees): the deformation would have to turn them over, which a fold-free
// step never does, so they stay where they are and block the polycube. The
// labeller reads labels off a straightened shape that turns whole parts (a
// curled trunk unrolls), so some faces of such parts get labels that fit the
// straightened normal and face away from the input's (the elephant: 376 of
// 5558 faces).
//
// Inputs:
//   mesh        the input (its Newell normals)
//   neighbours  face_neighbours (mesh_adjacency.h)
// In/out:
//   labels      per face, 0..5: a face facing away takes, of its edge
//               neighbours' labels, the one closest to its normal if it
//               faces that label's axis, else its nearest axis; sweeps until
//               none faces away (at most max_sweeps), each sweep decided
//               from the labels before it
// Returns the number of faces relabelled.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

int relabel_faces_facing_away(const PolygonMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                              std::vector<int>& labels, int max_sweeps = 10);

}  // namespace polycube
