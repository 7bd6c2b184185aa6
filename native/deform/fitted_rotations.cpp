#include "deform/fitted_rotations.h"

#include <Eigen/Geometry>
#include <cmath>

#include "deform/rodrigues.h"
#include "labels/axis.h"
#include "linear_algebra/parallel.h"
#include "linear_algebra/run_tasks.h"

namespace polycube {

Eigen::Matrix3d fitted_rotation(const Vertices& input, const Vertices& current, const Triangles& triangles,
                                const CotangentWeights& weights, const std::vector<int>& triangle_labels,
                                Eigen::Index t) {
  const Eigen::Vector3d axis = label_axis(triangle_labels[t]);
  Eigen::Vector3d p[3], q[3];
  for (int k = 0; k < 3; ++k) {
    p[k] = input.row(triangles(t, k));
    q[k] = current.row(triangles(t, k));
  }
  const Eigen::Vector3d input_normal = (p[1] - p[0]).cross(p[2] - p[0]);
  if (!(input_normal.norm() > 0.0)) {
    const Eigen::Vector3d normal = (q[1] - q[0]).cross(q[2] - q[0]);
    return normal.norm() > 0.0 ? rodrigues(normal.normalized(), axis) : Eigen::Matrix3d::Identity();
  }
  const Eigen::Matrix3d r0 = rodrigues(input_normal.normalized(), axis);
  double along = 0.0, across = 0.0, weight_sum = 0.0;
  for (int k = 0; k < 3; ++k) weight_sum += std::abs(weights(t, k));
  for (int k = 0; k < 3; ++k) {
    const int i = (k + 1) % 3, j = (k + 2) % 3;
    // Edges with zero weight still say something about the twist; a
    // triangle whose weights are all zero fits its three edges equally.
    const double w = weight_sum > 0.0 ? weights(t, k) : 1.0;
    const Eigen::Vector3d rotated = r0 * (p[i] - p[j]);
    const Eigen::Vector3d e = q[i] - q[j];
    along += w * e.dot(rotated);
    across += w * e.dot(axis.cross(rotated));
  }
  const double theta = (along == 0.0 && across == 0.0) ? 0.0 : std::atan2(across, along);
  return Eigen::AngleAxisd(theta, axis).toRotationMatrix() * r0;
}

Rotations fitted_rotations(const Vertices& input, const Vertices& current, const Triangles& triangles,
                           const CotangentWeights& weights, const std::vector<int>& triangle_labels) {
  Rotations rotations(triangles.rows());
  // A rotation costs about what four triangles' measurements do
  // (parallel.h's unit of work).
  run_in_parts(triangles.rows(), loop_parts(4 * triangles.rows()), [&](long begin, long end) {
    for (Eigen::Index t = begin; t < end; ++t)
      rotations[t] = fitted_rotation(input, current, triangles, weights, triangle_labels, t);
  });
  return rotations;
}

}  // namespace polycube
