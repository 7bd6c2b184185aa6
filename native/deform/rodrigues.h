// The rotation that turns unit vector n onto unit vector t (Rodrigues' formula
// about the axis n x t). Equal vectors give the identity; opposite ones a half
// turn about an axis perpendicular to n. Stable for every angle: beyond 90
// degrees it composes a half turn with the supplementary rotation, so the
// formula never divides by 1 + n.t near zero.
#pragma once

#include <Eigen/Core>

namespace polycube {

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& n, const Eigen::Vector3d& t);

}  // namespace polycube
