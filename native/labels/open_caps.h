// Open caps take one label (docs/design.md section 3.3): a connected
// component with a border (an eyeball, a leaf, a shell) that mostly looks
// one way is flattened best as one flat chart, the polycube a modeller would
// draw for it, not as a little open box of five charts around its rim. A
// chart with an open side meets the polycube conditions
// (charts_with_open_side), and a surface with a border can always be laid
// flat without folds; what decides is distortion: a cap whose area
// projected along its mean normal is at least half its area (a hemisphere
// or anything flatter) stretches at most by about that much.
//
// Inputs:
//   mesh       the input (its Newell normals, its components)
//   adjacency  mesh_adjacency of its faces
// In/out:
//   labels     per face, 0..5; every face of such a component takes the
//              axis nearest the component's area-weighted mean normal
// Returns the number of components relabelled.
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {

// |sum of area vectors| / area at which an open component counts as a cap.
constexpr double kCapMinFlatness = 0.5;

int label_open_caps(const PolygonMesh& mesh, const MeshAdjacency& adjacency, std::vector<int>& labels);

}  // namespace polycube
