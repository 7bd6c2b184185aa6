// Triangles that flat charts must squeeze onto a line, read from the labels
// alone (docs/design.md section 3.5).
//
// A polycube chart labelled +k or -k is flat: its vertices share one k
// coordinate. Every vertex of a triangle with axis k is on that plane, so
// charts of axis k that touch, even at one vertex, share one plane (the
// flat-chart solve, deform/chart_planes.h, merges them the same way). A
// triangle labelled with another axis whose three corners all lie on one
// plane of axis k has two coordinates pinned: it can only be a segment. Such
// triangles are "teeth" on a zigzag chart boundary and chart strips one
// triangle wide; measured, they are most of what flattening collapses
// (cactus: 7 of 7 collapsed triangles, eight: 18 of 19).
//
// Inputs:
//   vertex_count     number of vertices
//   triangles        #T by 3 corner indices
//   triangle_labels  #T labels 0..5 (-1: ignored)
// Outputs: per triangle, 1 when squeezed.
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// Per axis, the plane of each vertex: the union-find root of the vertices of
// that axis' triangles, -1 for vertices on no such triangle.
std::array<std::vector<int>, 3> axis_planes(int vertex_count, const Triangles& triangles,
                                            const std::vector<int>& triangle_labels);

std::vector<char> squeezed_triangles(int vertex_count, const Triangles& triangles,
                                     const std::vector<int>& triangle_labels);

// Relabels the polygon faces of squeezed triangles with the label of the
// chart that squeezes them (the label of the most triangles of that plane
// sharing their corners), round after round, until none is squeezed or
// `max_rounds` is reached. `face_of_triangle` maps triangles to the faces
// whose `labels` (0..5) are changed. Returns the number of faces relabelled.
int unsqueeze_labels(int vertex_count, const Triangles& triangles, const std::vector<int>& face_of_triangle,
                     std::vector<int>& labels, int max_rounds = 20);

}  // namespace polycube
