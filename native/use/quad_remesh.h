// An all-quad mesh from the polycube (docs/design.md section 1: quad meshing
// is one use of the polycube map). The chart planes of each axis are snapped
// to a grid of spacing h in order (quantise_planes), the squares of that grid
// are laid on every face of the quantised polycube, and every grid vertex is
// carried back onto the input surface through the polycube triangle that
// contains it (the same barycentric coordinates on the input triangle).
//
// So the result is all quads, manifold, closed where the input is closed, and
// its vertices of valence other than 4 sit only at polycube corners. Where the
// input is open, its boundary loops are first laid along grid lines on the
// polycube (straighten_boundaries), so rows of quads follow them and only their
// corners are irregular; a loop that cannot be laid so stays a staircase.
// Collapsed triangles carry no area: no grid square lands in them.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct QuadRemeshOptions {
  double edge_length = 0.0;  // target edge length h on the input (its units); > 0
  int relax_iterations = 10;  // sweeps of relax_on_surface evening the spacing on the input; 0: the grid as carried back
};

struct QuadRemesh {
  PolygonMesh mesh;               // quads, outward like the polycube's faces
  std::vector<int> source_face;   // per quad: the input face under its centre (for materials)
  std::vector<int> label;         // per quad: its polycube axis 0..5
  // Where each vertex lies on the input: three corners of one input face (indices into
  // faces.indices) and weights summing to 1, to carry per-corner data (UVs) over.
  Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor> vertex_corners;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> vertex_weights;
  double grid_spacing = 0.0;      // h in polycube units (edge_length times the polycube's scale)
  int irregular_vertices = 0;     // valence other than 4 (boundary vertices: other than 3)
  int open_edges = 0;             // edges with one quad (only where the input is open)
  int boundary_loops = 0;         // open boundary loops of the input
  int straightened_loops = 0;     // of those, laid along grid lines (straighten_boundaries)
};

// Inputs:
//   input     the mesh
//   polycube  #V by 3 positions on its exact polycube (every face that carries area flat on its axis)
//   labels    per face 0..5 or -1, or empty (see polycube_surface)
// Throws Error with one sentence: a polycube that does not fit, is folded or is
// not exact; an edge length that is not positive or larger than the model; a
// polycube that touches itself (its quads could not be manifold).
QuadRemesh quad_remesh(const PolygonMesh& input, const Vertices& polycube, const std::vector<int>& labels,
                       const QuadRemeshOptions& options);

}  // namespace polycube
