// Tangential relaxation of a mesh laid on a triangle surface: each vertex
// moves toward the mean of the neighbours it is given, within the surface's
// tangent plane there, and is put back on the surface at the nearest point
// found by walking outward from the triangle it was on (so it never jumps to
// another sheet of the surface across a thin gap) nor over a crease of the
// surface; a point on a triangle touching a crease stays where it is.
//
// Why the quad remesh needs it: grid points carried back through the
// polycube land unevenly where the polycube map is uneven. A strip of the
// input that the polycube collapsed onto an edge gets no grid point and is
// bridged by one long quad; a near-collapsed sliver stretches its few points
// far apart. Evening the spacing on the input itself samples those parts too
// (docs/design.md section 1: quad meshing is one use of the polycube map).
// Evening the spacing is not the goal in itself, though: moved from a flat
// part onto a curved one (a thin ear's rim), the same quads sag further off
// the surface. So a move that lets one of the point's faces sag further (its
// centre or an edge's midpoint further from the surface) is not made, and
// the faces' largest distance to the surface never grows.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// A point of a triangle surface: its triangle and barycentric weights there.
struct SurfacePoint {
  int triangle = -1;
  Eigen::Vector3d weights = Eigen::Vector3d::Constant(1.0 / 3.0);
};

// Inputs:
//   surface, triangles  the surface
//   neighbours          per vertex, the vertices whose mean it moves toward (none: it stays)
//   iterations          sweeps (each moves every vertex half way to its target)
//   faces               the faces the points make (indices into points), or none: each move is
//                       then made whatever it does to them
//   crease_degrees      an edge whose triangles' normals are further apart is a crease
// In/out:
//   points              per vertex, where it lies on the surface (a triangle of it)
// Returns the positions of the points.
Vertices relax_on_surface(const Vertices& surface, const Triangles& triangles,
                          const std::vector<std::vector<int>>& neighbours, int iterations,
                          std::vector<SurfacePoint>& points, const PolygonFaces& faces = {},
                          double crease_degrees = 80.0);

// The point of the surface's triangle t at its weights.
Eigen::Vector3d surface_position(const Vertices& surface, const Triangles& triangles, const SurfacePoint& p);

}  // namespace polycube
