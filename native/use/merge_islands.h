// Merges neighbouring UV islands whose union still unfolds well: fewer islands
// and shorter seams. Greedy, longest shared seam first; a union is kept when it
// is a disk, its conformal unfolding (relax_islands) turns no triangle over, its
// boundary does not cross itself, and its angle distortion stays within
// `slack` of its parts' (area-weighted). Charts that meet across a bend of the
// polycube but whose input surface is nearly developable there merge at no cost.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// Inputs:
//   input           the mesh
//   island_of_face  per face, changed in place (renumbered 0..islands-1)
//   islands         changed in place
//   uvs             #corners by 2, conformal islands (relax_islands), changed for merged islands
//   area_scale      as for relax_islands
//   slack           largest rise of angle distortion a merge may cost
void merge_islands(const PolygonMesh& input, std::vector<int>& island_of_face, int& islands, CornerUvs& uvs,
                   double area_scale, double slack);

}  // namespace polycube
