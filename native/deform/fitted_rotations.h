// The local step of the `robust` variant: for every triangle, the rotation
// that turns its *input* normal onto its label axis and, among those, the one
// whose in-plane twist best fits the triangle's current shape.
//
// This is the as-rigid-as-possible local step (Sorkine and Alexa 2007) with
// the normal constraint of Zhao and Gortler's stretching energy: minimise
//   sum_k w_k |e_k - R E_k|^2  over rotations R with R n_input = axis,
// where E_k are the input edges and e_k the current ones. Writing
// R = Q(theta) R0 with R0 = rodrigues(n_input, axis) and Q a turn about the
// axis, only theta is free and it has a closed form (2D Procrustes):
//   theta = atan2(sum w_k e_k . (axis x R0 E_k), sum w_k e_k . R0 E_k).
// Because targets come from the input triangle, the global solve pulls every
// triangle towards its own input shape: this is what cuts edge and area error
// and keeps triangles from folding, unlike the paper's step, which re-uses
// the current (possibly already squeezed) shape as its target.
#pragma once

#include <Eigen/Core>
#include <vector>

#include "linear_algebra/cotangent_weights.h"

namespace polycube {

using Rotations = std::vector<Eigen::Matrix3d>;

// A triangle of zero input area has no input normal: it takes the rotation of
// its current normal onto its axis (the paper's), or the identity when it has
// no current normal either.
// Triangle t's alone, as fitted_rotations() gives it: for a caller that uses
// each once (rotated_edges_rhs.h), without the list.
Eigen::Matrix3d fitted_rotation(const Vertices& input, const Vertices& current, const Triangles& triangles,
                                const CotangentWeights& weights, const std::vector<int>& triangle_labels,
                                Eigen::Index t);
Rotations fitted_rotations(const Vertices& input, const Vertices& current, const Triangles& triangles,
                           const CotangentWeights& weights, const std::vector<int>& triangle_labels);

}  // namespace polycube
