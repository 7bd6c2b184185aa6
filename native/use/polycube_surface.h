// What the UV map and the quad remesh read from a finished polycube: which
// faces carry area, the label each face ended with, and the checks that make
// the map from the input onto the polycube usable (same mesh, no folds).
//
// The labels are read from the polycube itself: a face that carries area lies
// in a plane, and its normal names its axis (docs/design.md section 4). Faces
// the solver collapsed onto an edge or a corner carry no area and no normal:
// they take the label given for them, else that of a neighbour. So the
// solver's final labels come out even where it relabelled faces.
#pragma once

#include <vector>

#include "mesh/mesh.h"
#include "mesh/triangulate.h"

namespace polycube {

struct PolycubeSurface {
  // Of the input's polygons, except those whose split would turn a triangle over on
  // the polycube (a polygon that is not convex there): those are split as on the polycube.
  Triangulation triangulation;
  std::vector<int> face_label;           // per polygon face, 0..5
  std::vector<char> face_carries_area;   // per polygon face: not collapsed
  double area_scale = 1.0;               // sqrt(polycube area / input area), the s of section 4
  double diagonal = 0.0;                 // of the polycube's bounding box
};

// Inputs:
//   input     the mesh (vertices, polygon faces)
//   polycube  #V by 3 positions of the same vertices on the polycube
//   labels    per face 0..5 (-1: from the polycube), or empty: all from the polycube
// Throws Error with one sentence when the polycube does not fit the mesh
// (vertex count, non-finite positions, no area), or is folded: a face that
// carries area facing away from its given label (a flipped face), or two
// neighbouring faces facing opposite ways (a folded edge) where the input does not.
PolycubeSurface polycube_surface(const PolygonMesh& input, const Vertices& polycube,
                                 const std::vector<int>& labels);

}  // namespace polycube
