#include "core/poisson_rhs.h"

#include <Eigen/Geometry>

#include "core/axis.h"
#include "core/parallel.h"
#include "core/rodrigues.h"

namespace polycube {

Vertices poisson_rhs(const Vertices& vertices, const Triangles& triangles, const CotangentWeights& weights,
                     const std::vector<int>& triangle_labels) {
  // Each thread scatters into its own copy of b; the copies are summed after.
  // Cheaper than atomics, and the sum is in a fixed order, so the result does
  // not depend on scheduling.
  const int threads = parallel_threads(triangles.rows());
  std::vector<Vertices> partial(threads, Vertices::Zero(vertices.rows(), 3));
#pragma omp parallel for num_threads(threads) schedule(static)
  for (int part = 0; part < threads; ++part) {
    Vertices& b = partial[part];
    const Eigen::Index begin = triangles.rows() * part / threads, end = triangles.rows() * (part + 1) / threads;
    for (Eigen::Index t = begin; t < end; ++t) {
      const Eigen::Vector3d p[3] = {vertices.row(triangles(t, 0)), vertices.row(triangles(t, 1)),
                                    vertices.row(triangles(t, 2))};
      const Eigen::Vector3d normal = (p[1] - p[0]).cross(p[2] - p[0]);
      const double length = normal.norm();
      const Eigen::Matrix3d rotation = length > 0.0
                                           ? rodrigues(normal / length, label_axis(triangle_labels[t]))
                                           : Eigen::Matrix3d::Identity();
      for (int k = 0; k < 3; ++k) {
        const int i = (k + 1) % 3, j = (k + 2) % 3;
        const Eigen::Vector3d term = weights(t, k) * (rotation * (p[i] - p[j]));
        b.row(triangles(t, i)) += term.transpose();
        b.row(triangles(t, j)) -= term.transpose();
      }
    }
  }
  for (int part = 1; part < threads; ++part) partial[0] += partial[part];
  return std::move(partial[0]);
}

}  // namespace polycube
