// The labeller's energy of a labeling (docs/design.md section 3.3), for
// alpha_expansion and for the repairs that compare moves:
//
//   E = sum over faces of area * (fidelity(normal, label axis) + against(input normal, label axis))
//     + compactness * sum over edges between charts of length * h * crease(normals) * V(a, b)
//
// Fidelity is 0 where the normal is the axis and near 1 from about 50 degrees
// on (PolyCut's Gaussian falloff); beyond 90 degrees it rises again, on the
// shape's normal and on the input's, so charts do not point away from their
// axes. V is 1 between orthogonal labels and 4 between opposite ones; crease
// lowers the weight across sharp edges, so boundaries follow features; h is
// a length proportional to the model's size, so the energy does not depend
// on the mesh resolution. Costs are in units of the mean face area.
//
// Inputs:
//   mesh         the shape whose normals the labels follow (the straightened
//                shape in the labeller, the input itself elsewhere)
//   input        the input's positions (same vertices): areas and the
//                against-input term
//   adjacency    mesh_adjacency of the faces
//   compactness  weight of chart boundaries (AutoLabelOptions)
#pragma once

#include "labels/alpha_expansion.h"
#include "mesh/mesh.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {

// The labeller's default compactness (detail 0.5, AutoLabelOptions).
constexpr double kDefaultCompactness = 0.3;

LabelEnergy label_energy(const PolygonMesh& mesh, const Vertices& input, const MeshAdjacency& adjacency,
                         double compactness);

}  // namespace polycube
