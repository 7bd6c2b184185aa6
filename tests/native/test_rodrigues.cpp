#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <random>

#include "deform/rodrigues.h"

using polycube::rodrigues;

namespace {

void expect_rotation_onto(const Eigen::Vector3d& n, const Eigen::Vector3d& t) {
  const Eigen::Matrix3d r = rodrigues(n, t);
  EXPECT_LT((r * n - t).norm(), 1e-12) << "n = " << n.transpose() << ", t = " << t.transpose();
  EXPECT_LT((r.transpose() * r - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(r.determinant(), 1.0, 1e-12);
}

TEST(Rodrigues, RandomPairsTurnNOntoT) {
  std::mt19937 random(7);
  std::normal_distribution<double> gauss;
  for (int k = 0; k < 10000; ++k) {
    const Eigen::Vector3d n = Eigen::Vector3d(gauss(random), gauss(random), gauss(random)).normalized();
    const Eigen::Vector3d t = Eigen::Vector3d(gauss(random), gauss(random), gauss(random)).normalized();
    expect_rotation_onto(n, t);
  }
}

TEST(Rodrigues, EqualVectorsGiveIdentity) {
  const Eigen::Vector3d n = Eigen::Vector3d(1, 2, 3).normalized();
  EXPECT_LT((rodrigues(n, n) - Eigen::Matrix3d::Identity()).norm(), 1e-15);
}

TEST(Rodrigues, OppositeVectorsGiveAHalfTurn) {
  const Eigen::Vector3d cases[] = {Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ(),
                                   Eigen::Vector3d(1, -2, 0.5).normalized()};
  for (const Eigen::Vector3d& n : cases) {
    expect_rotation_onto(n, -n);
    // A half turn: trace -1.
    EXPECT_NEAR(rodrigues(n, -n).trace(), -1.0, 1e-12);
  }
}

TEST(Rodrigues, NearlyOppositeAndNearlyEqualStayAccurate) {
  const Eigen::Vector3d t = Eigen::Vector3d::UnitZ();
  for (double e : {1e-3, 1e-7, 1e-10, 1e-14}) {
    expect_rotation_onto(Eigen::Vector3d(e, 0, -1).normalized(), t);
    expect_rotation_onto(Eigen::Vector3d(e, e, 1).normalized(), t);
  }
}

TEST(Rodrigues, RotatesAboutTheCommonPerpendicular) {
  // The axis of the rotation is n x t: it stays fixed.
  const Eigen::Vector3d n = Eigen::Vector3d(0.3, -0.8, 0.52).normalized(), t = Eigen::Vector3d::UnitY();
  const Eigen::Vector3d axis = n.cross(t).normalized();
  EXPECT_LT((rodrigues(n, t) * axis - axis).norm(), 1e-12);
}

}  // namespace
