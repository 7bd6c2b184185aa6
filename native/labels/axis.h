// Labels 0..5 name the six axis directions +X, -X, +Y, -Y, +Z, -Z; -1 is unlabelled.
#pragma once

#include <Eigen/Core>
#include <array>

namespace polycube {

constexpr int kUnlabelled = -1;
constexpr std::array<const char*, 6> kLabelNames{"+X", "-X", "+Y", "-Y", "+Z", "-Z"};

// The unit vector of a label 0..5.
inline Eigen::Vector3d label_axis(int label) {
  Eigen::Vector3d a = Eigen::Vector3d::Zero();
  a[label / 2] = (label % 2 == 0) ? 1.0 : -1.0;
  return a;
}

// The label whose axis is closest to direction n (any length). Ties go to the
// lower label so the result is deterministic; a zero vector gives +X.
inline int nearest_axis(const Eigen::Vector3d& n) {
  int best = 0;
  double best_value = -1.0;
  for (int k = 0; k < 3; ++k) {
    const double value = std::abs(n[k]);
    if (value > best_value) {
      best_value = value;
      best = 2 * k + (n[k] < 0.0 ? 1 : 0);
    }
  }
  return best;
}

}  // namespace polycube
