// The right-hand side of the Poisson solve for given per-triangle rotations:
// each edge (v, w) of triangle t with weight c adds c R_t (s_v - s_w) to b_v and
// subtracts it from b_w, where s are the source positions the edges are taken
// from. With s = the current positions and R_t = the paper's rotations this is
// poisson_rhs; the `robust` variant takes s = the input positions and the
// fitted rotations (an as-rigid-as-possible global step).
#pragma once

#include "core/cotangent_weights.h"
#include "core/fitted_rotations.h"

namespace polycube {

Vertices rotated_edges_rhs(const Vertices& source, const Triangles& triangles, const CotangentWeights& weights,
                           const Rotations& rotations);

}  // namespace polycube
