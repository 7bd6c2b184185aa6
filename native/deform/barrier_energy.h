// The untangling's energy of one triangle (deform/untangle_flat_charts.h) as
// a function of its 2 x 2 Jacobian J, with its gradient and Hessian in J:
// Garanzha et al. 2021's regularised barrier, with
// chi(d) = (d + sqrt(eps^2 + d^2)) / 2 of d = det J,
// weight ((1 - theta) |J|^2 + theta (d^2 + 1)) / chi(d).
//
// Why its own file: the untangler's Newton steps need the Hessian, made
// positive semi-definite here, in J (a 4 x 4 eigen-decomposition per
// triangle), before the triangle's linear map carries it to its corners,
// which keeps it so; tests check both derivatives against finite differences.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

namespace polycube {

// Returns the energy; `gradient`, when not null, receives its derivative by
// each entry of J. Inline: L-BFGS's untangling calls it for every triangle
// and every gradient, and its arithmetic is that untangling's, operation
// for operation (the minimisation is not convex: a rounding changed here
// changes which triangles end collapsed).
[[gnu::always_inline]] inline double barrier_energy(const Eigen::Matrix2d& j, double weight, double eps, double theta,
                                                Eigen::Matrix2d* gradient = nullptr) {
  const double d = j.determinant();
  const double root = std::sqrt(eps * eps + d * d);
  const double chi = 0.5 * (d + root), chi_d = 0.5 * (1.0 + d / root);
  const double frobenius = j.squaredNorm();
  const double value = weight * ((1.0 - theta) * frobenius + theta * (d * d + 1.0)) / chi;
  if (!gradient) return value;
  Eigen::Matrix2d cofactor;  // d det / d J
  cofactor << j(1, 1), -j(1, 0), -j(0, 1), j(0, 0);
  const double by_d = ((1.0 - theta) * -frobenius / (chi * chi) * chi_d +
                       theta * (2.0 * d / chi - (d * d + 1.0) / (chi * chi) * chi_d));
  *gradient = weight * ((1.0 - theta) * 2.0 / chi * j + by_d * cofactor);
  return value;
}

// The Hessian by J's four entries in column-major order (J(c, k) at c + 2 k).
// `project`: its negative eigenvalues replaced by their absolute values
// (positive semi-definite; where the barrier holds a triangle turned over,
// Newton's steps then keep their length, where setting them to 0 made the
// steps a hundred times shorter: elephant, 50 iterations from 44.7 to 38.9
// against 15 to 3.5), else exact.
Eigen::Matrix4d barrier_hessian(const Eigen::Matrix2d& j, double weight, double eps, double theta,
                                bool project = true);

}  // namespace polycube
