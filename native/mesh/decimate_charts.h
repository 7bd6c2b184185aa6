// A coarse copy of a labelled triangle mesh that keeps its charts, and the
// map that carries positions from the coarse copy back to the fine mesh.
//
// A mesh of a million triangles bends into its polycube far faster when the
// solver works on a few thousand and the result is carried back (docs/design.md
// section 2.8, coarse to fine). That only works if the coarse mesh has the same
// charts (edge-connected faces of one label) as the fine one and if every fine
// vertex is tied to the right part of it: each fine vertex gets a home, a
// coarse triangle and barycentric coordinates in it, on the coarse faces of its
// own chart, or on the coarse boundary between its own two charts. A coarse
// polycube carried back then leaves every fine chart exactly as flat as the
// coarse one.
//
// The coarse mesh is made by half-edge collapses only (a vertex moved onto a
// neighbour, no new positions), cheapest first by the Garland-Heckbert
// quadric of the fine triangles, with a small squared-distance term so that
// flat charts, where every plane error is zero, coarsen evenly. A collapse is
// refused when it would move a vertex where three or more charts meet, move a
// vertex off its chart boundary, change the mesh's topology, turn or flatten
// a triangle, remove a chart from a vertex, or leave a fine vertex without a
// home in its chart.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct Decimation {
  std::vector<int> kept;         // coarse vertex i is fine vertex kept[i], at the same position
  Triangles triangles;           // coarse triangles, indices into `kept`, oriented as the fine faces they replace
  std::vector<int> labels;       // per coarse triangle: its chart's label
  std::vector<int> charts;       // per coarse triangle: its chart, numbered as fine_charts
  std::vector<int> fine_charts;  // per fine triangle: its chart, numbered by lowest triangle
  // Per fine vertex: the coarse triangle it lies in, and its coordinates in
  // that triangle's corners (a point on an edge has exactly 0 at the third
  // corner). A kept vertex has 1 at its own corner; a vertex in no triangle
  // is kept with home -1.
  std::vector<int> home;
  Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor> barycentric;
  // Per fine triangle: the coarse triangle holding most of its corners' homes
  // (ties to the first corner), about where the fine face's centroid lands.
  std::vector<int> face_home;
};

// labels: one per triangle, 0..5. Collapses stop once at most
// target_triangles remain or none is allowed. Vertices in non-manifold parts,
// on zero-area triangles or where three charts meet (two at an open border)
// are never removed. Throws Error on a label count or value that is wrong, an
// index out of range, a non-finite coordinate or target_triangles < 1.
Decimation decimate_charts(const Vertices& vertices, const Triangles& triangles, const std::vector<int>& labels,
                           int target_triangles);

// The fine positions for coarse vertex positions (row i for coarse vertex i):
// each fine vertex at its home's barycentric combination. Throws Error when
// the row count is not the coarse vertex count.
Vertices carry_to_fine(const Decimation& decimation, const Vertices& coarse_positions);

}  // namespace polycube
