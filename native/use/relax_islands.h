// Conformal relaxation of UV islands (least-squares conformal maps, Lévy et
// al. 2002), started from the polycube's islands: each island keeps its
// faces, seams and orientation, but its inside is re-solved to preserve the
// input's angles, and faces the polycube collapsed get area again. Each island
// is then scaled to the input area it covers (times the polycube's scale), so
// texel density stays one over the model.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// Inputs:
//   input           the mesh (its 3D shape is what the map should be conformal to)
//   island_of_face  per face, 0..islands-1
//   uvs             #corners by 2: the islands' starting UVs, changed in place; corners of one
//                   island at one vertex must agree (they become one unknown)
//   area_scale      island UV area = area_scale^2 times its input area
// Two vertices of each island, far apart in the starting UVs, are pinned there.
void relax_islands(const PolygonMesh& input, const std::vector<int>& island_of_face, int islands, CornerUvs& uvs,
                   double area_scale);

}  // namespace polycube
