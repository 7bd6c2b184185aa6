// The untangling's energy of one triangle (deform/untangle_flat_charts.h) as
// a function of its 2 x 2 Jacobian J, with its gradient and Hessian in J:
// Garanzha et al. 2021's regularised barrier, with
// chi(d) = (d + sqrt(eps^2 + d^2)) / 2 of d = det J,
// weight ((1 - theta) |J|^2 + theta (d^2 + 1)) / chi(d).
//
// Why its own file: the untangler's Newton steps need the Hessian, made
// positive semi-definite here, in J (from its eigensystem in closed form),
// before the triangle's linear map carries it to its corners, which keeps it
// so; tests check both derivatives against finite differences and the
// projection against an iterative eigen-decomposition.
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

// barrier_energy() of kLanes Jacobians side by side: entry J(c, k) of lane
// i at j[c + 2 k][i], likewise the gradient; every lane the same operations
// in the same order as barrier_energy(), so the same values bit for bit (the
// untangling's outcome does not move; a test compares them). Why: one
// triangle's energy is a chain of a square root and six divisions, each
// waiting for the last, and the untangling spends most of its time in it;
// lanes side by side keep the core busy and fill its vector units.
template <int kLanes>
[[gnu::always_inline]] inline void barrier_energy_lanes(const double (&j)[4][kLanes], const double (&weight)[kLanes],
                                                        double eps, double theta, double (&value)[kLanes],
                                                        double (*gradient)[kLanes] = nullptr) {
  double chi[kLanes], chi_d[kLanes], d[kLanes], frobenius[kLanes];
  for (int i = 0; i < kLanes; ++i) {
    d[i] = j[0][i] * j[3][i] - j[1][i] * j[2][i];
    const double root = std::sqrt(eps * eps + d[i] * d[i]);
    chi[i] = 0.5 * (d[i] + root);
    chi_d[i] = 0.5 * (1.0 + d[i] / root);
    // Eigen's order for the four squares (two packets of two, then their sum).
    frobenius[i] = (j[0][i] * j[0][i] + j[2][i] * j[2][i]) + (j[1][i] * j[1][i] + j[3][i] * j[3][i]);
    value[i] = weight[i] * ((1.0 - theta) * frobenius[i] + theta * (d[i] * d[i] + 1.0)) / chi[i];
  }
  if (!gradient) return;
  for (int i = 0; i < kLanes; ++i) {
    const double by_d = ((1.0 - theta) * -frobenius[i] / (chi[i] * chi[i]) * chi_d[i] +
                         theta * (2.0 * d[i] / chi[i] - (d[i] * d[i] + 1.0) / (chi[i] * chi[i]) * chi_d[i]));
    const double by_j = (1.0 - theta) * 2.0 / chi[i];
    // d det / d J, entry by entry: J(1, 1), -J(0, 1), -J(1, 0), J(0, 0).
    gradient[0][i] = weight[i] * (by_j * j[0][i] + by_d * j[3][i]);
    gradient[1][i] = weight[i] * (by_j * j[1][i] + by_d * -j[2][i]);
    gradient[2][i] = weight[i] * (by_j * j[2][i] + by_d * -j[1][i]);
    gradient[3][i] = weight[i] * (by_j * j[3][i] + by_d * j[0][i]);
  }
}

// The Hessian by J's four entries in column-major order (J(c, k) at c + 2 k).
// `project`: its negative eigenvalues replaced by their absolute values
// (positive semi-definite; where the barrier holds a triangle turned over,
// Newton's steps then keep their length, where setting them to 0 made the
// steps a hundred times shorter: elephant, 50 iterations from 44.7 to 38.9
// against 15 to 3.5), else exact.
Eigen::Matrix4d barrier_hessian(const Eigen::Matrix2d& j, double weight, double eps, double theta, bool project = true);

}  // namespace polycube
