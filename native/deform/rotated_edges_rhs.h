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

namespace polycube {

// `rotation(t)` gives R_t, so a caller can compute it on the fly rather than
// store one matrix per triangle. Each thread scatters into its own copy of b
// and the copies are summed after: cheaper than atomics, and the sum is in a
// fixed order, so the result does not depend on scheduling.
template <class RotationOfTriangle>
Vertices rotated_edges_rhs(const Vertices& source, const Triangles& triangles, const CotangentWeights& weights,
                           const RotationOfTriangle& rotation) {
  const int threads = parallel_threads(triangles.rows());
  std::vector<Vertices> partial(threads, Vertices::Zero(source.rows(), 3));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int part = 0; part < threads; ++part) {
    Vertices& b = partial[part];
    const Eigen::Index begin = triangles.rows() * part / threads, end = triangles.rows() * (part + 1) / threads;
    for (Eigen::Index t = begin; t < end; ++t) {
      const Eigen::Matrix3d r = rotation(t);
      for (int k = 0; k < 3; ++k) {
        const int i = triangles(t, (k + 1) % 3), j = triangles(t, (k + 2) % 3);
        const Eigen::Vector3d edge = source.row(i) - source.row(j);
        const Eigen::Vector3d term = weights(t, k) * (r * edge);
        b.row(i) += term.transpose();
        b.row(j) -= term.transpose();
      }
    }
  }
  for (int part = 1; part < threads; ++part) partial[0] += partial[part];
  return std::move(partial[0]);
}

inline Vertices rotated_edges_rhs(const Vertices& source, const Triangles& triangles, const CotangentWeights& weights,
                                  const Rotations& rotations) {
  return rotated_edges_rhs(source, triangles, weights, [&](Eigen::Index t) { return rotations[t]; });
}

}  // namespace polycube
