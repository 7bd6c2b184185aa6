#include "deform/rodrigues.h"

#include <Eigen/Geometry>

namespace polycube {
namespace {

Eigen::Matrix3d cross_matrix(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Valid for n.t >= 0, where 1 / (1 + n.t) <= 1.
Eigen::Matrix3d rotation_within_90(const Eigen::Vector3d& n, const Eigen::Vector3d& t) {
  const Eigen::Matrix3d k = cross_matrix(n.cross(t));
  return Eigen::Matrix3d::Identity() + k + k * k / (1.0 + n.dot(t));
}

// Any unit vector perpendicular to n.
Eigen::Vector3d perpendicular(const Eigen::Vector3d& n) {
  const Eigen::Vector3d other =
      std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return n.cross(other).normalized();
}

}  // namespace

Eigen::Matrix3d rodrigues(const Eigen::Vector3d& n, const Eigen::Vector3d& t) {
  if (n.dot(t) >= 0.0) return rotation_within_90(n, t);
  // A half turn about an axis perpendicular to both n and t sends n to -n and
  // keeps the rotation in the plane of n and t; the rest is within 90 degrees.
  const Eigen::Vector3d c = n.cross(t);
  const double c_norm = c.norm();
  const Eigen::Vector3d a = c_norm > 1e-12 ? Eigen::Vector3d(c / c_norm) : perpendicular(n);
  const Eigen::Matrix3d half_turn = 2.0 * a * a.transpose() - Eigen::Matrix3d::Identity();
  return rotation_within_90(-n, t) * half_turn;
}

}  // namespace polycube
