// Triangles of a moved polycube turned over, opened again inside their charts.
//
// Why: straighten_boundaries moves an open boundary onto grid lines and fades
// the move into the polycube by a harmonic field; where a loop runs slantwise
// across charts its runs move by steps, more than the thin triangles along
// it are wide, and the field turns some of them over. The boundary's new
// place is fine; the triangles inside need other places in their planes.
//
// How: over the free coordinates only (a vertex keeps every plane it lies on
// and every coordinate the caller holds, so the charts stay flat and where
// they were), minimise each triangle's distortion from its shape on the
// reference polycube, measured in its chart's plane, with the regularised
// barrier of Garanzha et al. 2021 ("Foldover-free maps in 50 lines of
// code"): with chi(d) = (d + sqrt(eps^2 + d^2)) / 2 of the Jacobian's
// determinant d, E = sum area (|J|^2 / chi + (d^2 + 1) / chi) / 2, minimised
// again as eps shrinks, which takes turned-over triangles to positive area
// where the held coordinates leave room.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// Inputs:
//   reference  #V by 3, every counted triangle with positive area in its plane
//   positions  #V by 3 start (held coordinates already where they must be); improved in place
//   triangles  #T by 3
//   label      per triangle its axis 0..5 (its plane), or -1: not counted
//   free_axes  per vertex a bit mask of the axes it may move along
//   min_ratio  the share of its reference area every counted triangle must keep
// Returns whether every counted triangle touching a free coordinate keeps more than
// min_ratio of its reference area (the others are not looked at).
bool untangle_in_charts(const Vertices& reference, Vertices& positions, const Triangles& triangles,
                        const std::vector<int>& label, const std::vector<int>& free_axes, double min_ratio);

}  // namespace polycube
