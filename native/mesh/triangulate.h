// Splits polygon faces into triangles without adding vertices, so solver output
// maps 1:1 back onto the input vertices. Concave polygons are ear-clipped in the
// plane of their Newell normal; polygons too degenerate for that (collinear or
// repeated corners) fall back to a fan, which is as good as any split there.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct Triangulation {
  Triangles triangles;
  std::vector<int> face_of_triangle;  // the polygon each triangle came from
};

Triangulation triangulate(const Vertices& vertices, const PolygonFaces& faces);

// The Newell normal of a polygon: twice its vector area, exact for planar
// polygons and a sensible average for warped ones.
Eigen::Vector3d newell_normal(const Vertices& vertices, const PolygonFaces& faces, int face);

}  // namespace polycube
