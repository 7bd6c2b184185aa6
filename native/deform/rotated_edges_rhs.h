// The right-hand side of the Poisson solve for per-triangle rotations: each
// edge (v, w) of triangle t with weight c adds c R_t (s_v - s_w) to b_v and
// subtracts it from b_w, where s are the source positions the edges are taken
// from. With s = the current positions and R_t = the paper's rotations this is
// poisson_rhs; the `robust` variant takes s = the input positions and the
// fitted rotations (an as-rigid-as-possible global step).
#pragma once

#include <vector>

#include "linear_algebra/cotangent_weights.h"
#include "deform/fitted_rotations.h"
#include "linear_algebra/parallel.h"
#include "linear_algebra/run_tasks.h"

namespace polycube {

// `rotation(t)` gives R_t, so a caller can compute it on the fly rather than
// store one matrix per triangle. Each triangle's three terms are computed in
// parts on the task threads (run_tasks.h), then added to b triangle by
// triangle on one thread: the same sums on any number of cores.
template <class RotationOfTriangle>
Vertices rotated_edges_rhs(const Vertices& source, const Triangles& triangles, const CotangentWeights& weights,
                           const RotationOfTriangle& rotation) {
  const Eigen::Index count = triangles.rows();
  std::vector<Eigen::Matrix3d> terms(count);  // column k: the term of the edge opposite corner k
  run_in_parts(count, loop_parts(count), [&](long begin, long end) {
    for (Eigen::Index t = begin; t < end; ++t) {
      const Eigen::Matrix3d r = rotation(t);
      for (int k = 0; k < 3; ++k) {
        const int i = triangles(t, (k + 1) % 3), j = triangles(t, (k + 2) % 3);
        const Eigen::Vector3d edge = source.row(i) - source.row(j);
        terms[t].col(k) = weights(t, k) * (r * edge);
      }
    }
  });
  Vertices b = Vertices::Zero(source.rows(), 3);
  for (Eigen::Index t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) {
      const int i = triangles(t, (k + 1) % 3), j = triangles(t, (k + 2) % 3);
      b.row(i) += terms[t].col(k).transpose();
      b.row(j) -= terms[t].col(k).transpose();
    }
  return b;
}

inline Vertices rotated_edges_rhs(const Vertices& source, const Triangles& triangles, const CotangentWeights& weights,
                                  const Rotations& rotations) {
  return rotated_edges_rhs(source, triangles, weights, [&](Eigen::Index t) { return rotations[t]; });
}

// The fitting's right-hand side (fit_step.h, flatten_charts.h): the input's
// edges turned by the rotations fitted to `current`, plus the Laplacian's
// diagonal `shift` times `current` (deformation.h).
inline Eigen::MatrixX3d fitted_rhs(const Vertices& input, const Vertices& current, const Triangles& triangles,
                                   const std::vector<int>& triangle_labels, const CotangentWeights& weights,
                                   double shift) {
  return rotated_edges_rhs(input, triangles, weights,
                           [&](Eigen::Index t) {
                             return fitted_rotation(input, current, triangles, weights, triangle_labels, t);
                           }) +
         shift * current;
}

}  // namespace polycube
