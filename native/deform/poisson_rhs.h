// One iteration's right-hand side (docs/design.md section 2): every triangle turns
// its current normal onto its target axis with a rotation R_f, and each edge
// (v, w) with weight c adds c R_f (x_v - x_w) to b_v and subtracts it from b_w
// (the paper's equation (2) prints a minus between the terms; the gradient of
// its energy gives this plus).
//
// Assembled per triangle, never per half-edge, so it needs no orientation and
// no manifold structure. A triangle with zero area has no normal to turn: it
// keeps R_f = I, which leaves its edges where L puts them.
#pragma once

#include <vector>

#include "linear_algebra/cotangent_weights.h"

namespace polycube {

Vertices poisson_rhs(const Vertices& vertices, const Triangles& triangles, const CotangentWeights& weights,
                     const std::vector<int>& triangle_labels);

}  // namespace polycube
