#include "deform/barrier_energy.h"

#include <Eigen/Cholesky>
#include <cmath>

namespace polycube {

namespace {

// The cosine and sine of half the angle whose cosine and sine are `c`, `s`
// (one of its two halves; the other is the opposite vector), without
// trigonometry.
Eigen::Vector2d half_angle(double c, double s) {
  if (c >= 0.0) {
    const double half_cos = std::sqrt(0.5 * (1.0 + c));
    return {half_cos, 0.5 * s / half_cos};
  }
  const double half_sin = std::copysign(std::sqrt(0.5 * (1.0 - c)), s);
  return {0.5 * s / half_sin, half_sin};
}

// (x, y) over its length; (1, 0) for the zero vector (any angle does).
// Not hypot: no overflow at these sizes, and its guard against one is slow.
Eigen::Vector2d direction(double x, double y) {
  const double length = std::sqrt(x * x + y * y);
  return length > 0.0 ? Eigen::Vector2d(x / length, y / length) : Eigen::Vector2d(1.0, 0.0);
}

// The projection of the Hessian h = psi_2 (2 I) + psi_d H_det + g M g^T of an
// energy psi(|J|^2, det J) (g: the two invariants' gradients, M: psi's
// second derivatives by them), from its eigensystem in closed form, as in
// Smith, de Goes and Kim 2019: with J = U diag(s1, s2) W, U and W rotations
// (s2 < 0 where J turns the triangle over), the twist U [0 -1; 1 0] W and
// the flip U [0 1; 1 0] W are eigenvectors (eigenvalues 2 psi_2 +- psi_d),
// the scalings U diag(1, 0) W and U diag(0, 1) W span the other two, from a
// 2 x 2 system. Why: a 4 x 4 iterative eigen-decomposition per triangle
// turned over was a fifth of the Newton untangling's time at scale.
Eigen::Matrix4d projected(const Eigen::Matrix2d& j, double psi_2, double psi_d, double psi_2d, double psi_dd) {
  // J's signed singular value decomposition in closed form: J = rot(phi)
  // diag(q + r, q - r) rot(theta), with phi + theta and phi - theta the
  // angles of (e, h) and (f, g).
  const double e = 0.5 * (j(0, 0) + j(1, 1)), f = 0.5 * (j(0, 0) - j(1, 1));
  const double g = 0.5 * (j(1, 0) + j(0, 1)), h = 0.5 * (j(1, 0) - j(0, 1));
  const double q = std::sqrt(e * e + h * h), r = std::sqrt(f * f + g * g);
  const double s1 = q + r, s2 = q - r;
  const Eigen::Vector2d sum = direction(e, h), difference = direction(f, g);
  // phi: half of the angles' sum; theta = phi - the difference's angle.
  const Eigen::Vector2d u1 = half_angle(sum.x() * difference.x() - sum.y() * difference.y(),
                                        sum.y() * difference.x() + sum.x() * difference.y());
  const Eigen::Vector2d u2(-u1.y(), u1.x());
  const double cos_theta = u1.x() * difference.x() + u1.y() * difference.y();
  const double sin_theta = u1.y() * difference.x() - u1.x() * difference.y();
  // W = rot(theta): its rows.
  const Eigen::Vector2d w1(cos_theta, -sin_theta), w2(sin_theta, cos_theta);
  auto vec = [](const Eigen::Vector2d& u, const Eigen::Vector2d& w) {  // u w^T, column-major
    return Eigen::Vector4d(u.x() * w.x(), u.y() * w.x(), u.x() * w.y(), u.y() * w.y());
  };
  const Eigen::Vector4d d1 = vec(u1, w1), d2 = vec(u2, w2);
  const Eigen::Vector4d twist = std::sqrt(0.5) * (vec(u2, w1) - vec(u1, w2));
  const Eigen::Vector4d flip = std::sqrt(0.5) * (vec(u2, w1) + vec(u1, w2));
  // The scalings' 2 x 2 block: 2 psi_2 I + psi_d [0 1; 1 0] + G M G^T, G's
  // rows the invariants' derivatives along d1 and d2: (2 s1, s2), (2 s2, s1).
  Eigen::Matrix2d gm;
  gm << 2.0 * s1, s2, 2.0 * s2, s1;
  Eigen::Matrix2d m;
  m << 0.0, psi_2d, psi_2d, psi_dd;
  Eigen::Matrix2d block = gm * m * gm.transpose();
  block.diagonal().array() += 2.0 * psi_2;
  block(0, 1) += psi_d;
  block(1, 0) += psi_d;
  // Its eigenvectors: the rotation by half the angle of (half_difference, off-diagonal).
  const double half_difference = 0.5 * (block(0, 0) - block(1, 1)), middle = 0.5 * (block(0, 0) + block(1, 1));
  const double radius = std::sqrt(half_difference * half_difference + block(0, 1) * block(0, 1));
  const Eigen::Vector2d towards = direction(half_difference, block(0, 1));
  const Eigen::Vector2d rotation = half_angle(towards.x(), towards.y());
  const double c = rotation.x(), s = rotation.y();
  const Eigen::Vector4d scale1 = c * d1 + s * d2, scale2 = -s * d1 + c * d2;
  return std::abs(2.0 * psi_2 + psi_d) * twist * twist.transpose() +
         std::abs(2.0 * psi_2 - psi_d) * flip * flip.transpose() +
         std::abs(middle + radius) * scale1 * scale1.transpose() +
         std::abs(middle - radius) * scale2 * scale2.transpose();
}

}  // namespace

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
  // Convex already (a Cholesky tells, at a fraction of the projection's cost).
  if (!project || Eigen::LLT<Eigen::Matrix4d>(h).info() == Eigen::Success) return h;
  // The energy as psi(|J|^2, det J) = weight N / chi: its derivatives by the
  // two invariants (psi_22 = 0: N is linear in |J|^2).
  const double numerator_d = 2.0 * theta * d;
  const double psi_2 = weight * (1.0 - theta) / chi;
  const double psi_d = weight * (numerator_d / chi - numerator * chi_d / (chi * chi));
  const double psi_2d = -weight * (1.0 - theta) * chi_d / (chi * chi);
  const double psi_dd =
      weight * (2.0 * theta / chi - 2.0 * numerator_d * chi_d / (chi * chi) - numerator * chi_dd / (chi * chi) +
                2.0 * numerator * chi_d * chi_d / (chi * chi * chi));
  return projected(j, psi_2, psi_d, psi_2d, psi_dd);
}

}  // namespace polycube
