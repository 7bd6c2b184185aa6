#include "deform/poisson_rhs.h"

#include <Eigen/Geometry>

#include "labels/axis.h"
#include "deform/rodrigues.h"
#include "deform/rotated_edges_rhs.h"

namespace polycube {

Vertices poisson_rhs(const Vertices& vertices, const Triangles& triangles, const CotangentWeights& weights,
                     const std::vector<int>& triangle_labels) {
  return rotated_edges_rhs(vertices, triangles, weights, [&](Eigen::Index t) -> Eigen::Matrix3d {
    const Eigen::Vector3d a = vertices.row(triangles(t, 0)), b = vertices.row(triangles(t, 1)),
                          c = vertices.row(triangles(t, 2));
    const Eigen::Vector3d normal = (b - a).cross(c - a);
    const double length = normal.norm();
    return length > 0.0 ? rodrigues(normal / length, label_axis(triangle_labels[t])) : Eigen::Matrix3d::Identity();
  });
}

}  // namespace polycube
