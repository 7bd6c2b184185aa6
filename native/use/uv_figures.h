// How good a UV map is, the same way for ours and for any other (Blender's
// Smart UV Project in the benchmark): the distortion of the map from the
// mesh onto the UV plane, its islands and its seams.
#pragma once

#include "mesh/mesh.h"

namespace polycube {

struct UvFigures {
  // Area-weighted means over the triangles whose UV image has area:
  double angle_distortion = 0.0;  // sigma_max / sigma_min of each triangle's map (1: conformal)
  double area_distortion = 0.0;   // max(r, 1/r), r = its share of the UV area over its share of the mesh area
  double collapsed_area = 0.0;    // share of the mesh area whose UV image is collapsed, as the polycube's
                                  // triangles are (below 1e-3 of their scaled input area; left out above)
  int flipped = 0;                // triangles whose UV image is turned over against the island's majority
  int islands = 0;                // faces joined across edges whose two ends keep their UVs
  double seam_length = 0.0;       // mesh length of the edges between two faces whose UVs part there
};

// Inputs:
//   mesh  the mesh (3D positions), polygon faces
//   uvs   per corner (faces.indices order)
UvFigures uv_figures(const PolygonMesh& mesh, const CornerUvs& uvs);

}  // namespace polycube
