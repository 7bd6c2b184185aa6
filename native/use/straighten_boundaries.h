// The open boundaries of a polycube laid straight along the quad grid, so that
// the quad remesh follows them with straight rows of quads.
//
// Where the input is open, its boundary crosses the polycube's charts as a
// curve that no axis governs: the grid's squares inside it make a staircase,
// every step two irregular vertices (valence 2 and 4 on the boundary). Here
// each boundary loop is cut into runs, each kept at one coordinate (like a
// polycube's charts, one dimension lower: a run goes along one grid axis, at
// a constant other one), each run's coordinate snapped to a grid line, and the
// boundary's vertices moved onto their runs within their charts' planes. The
// move fades into the polycube by a harmonic displacement (graph Laplacian),
// per axis, held at zero on every plane of that axis, so the polycube stays
// exact and its planes stay where they were. Triangles the field turns over
// are opened again inside their charts (untangle_in_charts); a triangle with
// all three corners on one run is laid flat on it (the remesh leaves it out).
// A run crossing a polycube edge goes straight across it (both sides keep the
// same coordinate, the edge's own direction), so the grid line it lies on
// continues on the other side; no run goes past a polycube edge along it. A
// loop whose move still turns a triangle over is planned again, its turns
// back within a chart split off as runs of their own and fewer runs joined
// (more corners, smaller moves, while those stay under two thirds of the
// turns its staircase would take); if none works it stays as it was.
#pragma once

#include <array>

#include "mesh/mesh.h"
#include "use/polycube_surface.h"
#include "use/quantise_planes.h"

namespace polycube {

struct StraightBoundaries {
  Vertices polycube;      // the polycube, its straightened boundaries moved onto grid lines
  int loops = 0;          // open boundary loops of the input
  int straightened = 0;   // of those, the ones moved
};

// Inputs:
//   input     the mesh
//   polycube  its exact polycube, #V by 3
//   surface   polycube_surface(input, polycube, ...)
//   grid      the quantised planes of each axis (quantise_planes), in polycube units
//   min_run   a run shorter than this (polycube units) between two runs at one coordinate joins them
//             where the three together stay within ten grid steps of a line
StraightBoundaries straighten_boundaries(const PolygonMesh& input, const Vertices& polycube,
                                         const PolycubeSurface& surface, const std::array<AxisGrid, 3>& grid,
                                         double min_run);

}  // namespace polycube
