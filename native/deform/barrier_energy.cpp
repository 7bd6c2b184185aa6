#include "deform/barrier_energy.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>

namespace polycube {

Eigen::Matrix4d barrier_hessian(const Eigen::Matrix2d& j, double weight, double eps, double theta, bool project) {
  const double d = j.determinant();
  const double root = std::sqrt(eps * eps + d * d);
  const double chi = 0.5 * (d + root), chi_d = 0.5 * (1.0 + d / root);
  const double chi_dd = 0.5 * eps * eps / (root * root * root);
  const double numerator = (1.0 - theta) * j.squaredNorm() + theta * (d * d + 1.0);
  const Eigen::Vector4d entries(j(0, 0), j(1, 0), j(0, 1), j(1, 1));
  const Eigen::Vector4d by_d(j(1, 1), -j(0, 1), -j(1, 0), j(0, 0));  // d det / d J
  const Eigen::Vector4d numerator_by = 2.0 * (1.0 - theta) * entries + 2.0 * theta * d * by_d;
  Eigen::Matrix4d det_hessian = Eigen::Matrix4d::Zero();
  det_hessian(0, 3) = det_hessian(3, 0) = 1.0;
  det_hessian(1, 2) = det_hessian(2, 1) = -1.0;
  const Eigen::Matrix4d outer = by_d * by_d.transpose();
  const Eigen::Matrix4d numerator_hessian =
      2.0 * (1.0 - theta) * Eigen::Matrix4d::Identity() + 2.0 * theta * (outer + d * det_hessian);
  const Eigen::Matrix4d cross = numerator_by * by_d.transpose();
  // (N / chi)'' = N'' / chi - chi' (N' d' + d' N') / chi^2 + N (2 chi'^2 / chi^3 - chi'' / chi^2) d' d'
  //               - N chi' / chi^2 d''
  Eigen::Matrix4d h = weight * (numerator_hessian / chi - chi_d / (chi * chi) * (cross + cross.transpose()) +
                                numerator * (2.0 * chi_d * chi_d / (chi * chi * chi) - chi_dd / (chi * chi)) * outer -
                                numerator * chi_d / (chi * chi) * det_hessian);
  // Convex already (a Cholesky tells, at a fraction of the eigen-decomposition's cost).
  if (!project || Eigen::LLT<Eigen::Matrix4d>(h).info() == Eigen::Success) return h;
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(h);
  return eigen.eigenvectors() * eigen.eigenvalues().cwiseAbs().asDiagonal() * eigen.eigenvectors().transpose();
}

}  // namespace polycube
