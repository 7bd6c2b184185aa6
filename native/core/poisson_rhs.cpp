#include "core/poisson_rhs.h"

#include <Eigen/Geometry>

#include "core/axis.h"
#include "core/rodrigues.h"

namespace polycube {

Vertices poisson_rhs(const Vertices& vertices, const Triangles& triangles, const CotangentWeights& weights,
                     const std::vector<int>& triangle_labels) {
  Vertices b = Vertices::Zero(vertices.rows(), 3);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
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
  return b;
}

}  // namespace polycube
