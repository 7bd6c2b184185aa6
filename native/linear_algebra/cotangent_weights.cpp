#include "linear_algebra/cotangent_weights.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "linear_algebra/parallel.h"

namespace polycube {

CotangentWeights cotangent_weights(const Vertices& vertices, const Triangles& triangles) {
  CotangentWeights weights(triangles.rows(), 3);
#pragma omp parallel for num_threads(parallel_threads(triangles.rows())) schedule(static)
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d p = vertices.row(triangles(t, k));
      const Eigen::Vector3d a = Eigen::Vector3d(vertices.row(triangles(t, (k + 1) % 3))) - p;
      const Eigen::Vector3d b = Eigen::Vector3d(vertices.row(triangles(t, (k + 2) % 3))) - p;
      const double sine = a.cross(b).norm();
      const double cosine = a.dot(b);
      // sine == 0 with cosine == 0 means coincident corners: no edge to weigh.
      double cotangent = 0.0;
      if (sine > 0.0) {
        cotangent = std::clamp(cosine / sine, -kMaxCotangent, kMaxCotangent);
      } else if (cosine != 0.0) {
        cotangent = cosine > 0.0 ? kMaxCotangent : -kMaxCotangent;
      }
      weights(t, k) = 0.5 * cotangent;
    }
  }
  return weights;
}

}  // namespace polycube
