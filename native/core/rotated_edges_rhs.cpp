#include "core/rotated_edges_rhs.h"

namespace polycube {

Vertices rotated_edges_rhs(const Vertices& source, const Triangles& triangles, const CotangentWeights& weights,
                           const Rotations& rotations) {
  Vertices b = Vertices::Zero(source.rows(), 3);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int i = triangles(t, (k + 1) % 3), j = triangles(t, (k + 2) % 3);
      const Eigen::Vector3d edge = source.row(i) - source.row(j);
      const Eigen::Vector3d term = weights(t, k) * (rotations[t] * edge);
      b.row(i) += term.transpose();
      b.row(j) -= term.transpose();
    }
  }
  return b;
}

}  // namespace polycube
