// Packs UV islands into the unit square without overlap: each island's
// bounding rectangle (turned upright when taller than wide) goes on a shelf,
// tallest first, and the shelf width that gives the smallest square wins.
// Every island is moved (and maybe turned by 90 degrees) rigidly, and all
// are scaled by one factor, so relative texel density is kept.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// Inputs:
//   uvs               #corners by 2, changed in place
//   island_of_corner  per corner, 0..island_count-1
//   padding           gap between islands relative to sqrt(total rectangle area)
void pack_islands(CornerUvs& uvs, const std::vector<int>& island_of_corner, int island_count, double padding);

}  // namespace polycube
