#include "labeller/straighten.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "deform/fitted_rotations.h"
#include "deform/rotated_edges_rhs.h"
#include "labels/axis.h"
#include "linear_algebra/cotangent_weights.h"
#include "linear_algebra/laplacian.h"
#include "linear_algebra/parallel.h"
#include "linear_algebra/sparse_cholesky.h"
#include "mesh/components.h"
#include "mesh/triangle_incidence.h"

namespace polycube {
namespace {

// Same as the deformation's shift (deform/deformation.h): definite, exact at fixed points.
constexpr double kRelativeShift = 1e-8;
// Agreement of two unit normals, (max(0, a.b))^4: 1 when parallel, 0.25 at
// 40 degrees, 0 from 90 degrees on.
double agreement(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double d = std::max(0.0, a.dot(b)), d2 = d * d;
  return d2 * d2;
}

// The triangles sharing a corner with each triangle (itself included), each once.
std::vector<std::vector<int>> corner_neighbours(Eigen::Index vertex_count, const Triangles& triangles) {
  const TriangleIncidence incidence(vertex_count, triangles);
  std::vector<std::vector<int>> neighbours(triangles.rows());
#pragma omp parallel for num_threads(parallel_threads(triangles.rows())) schedule(static)
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    std::vector<int>& list = neighbours[t];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, k);
      list.insert(list.end(), incidence.triangles.begin() + incidence.offsets[v],
                  incidence.triangles.begin() + incidence.offsets[v + 1]);
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

}  // namespace

Vertices straighten(const Vertices& input, const Triangles& triangles, const StraightenOptions& options) {
  const int n = static_cast<int>(input.rows());
  const Eigen::Index m = triangles.rows();
  Vertices x = input;
  if (options.iterations <= 0 || m == 0) return x;

  const CotangentWeights weights = cotangent_weights(input, triangles).cwiseMax(0.0);
  Laplacian laplacian(n, triangles);
  const double shift = laplacian.assemble(weights, kRelativeShift);
  SparseCholesky cholesky;
  cholesky.analyze(laplacian.matrix());
  cholesky.factorize(laplacian.matrix());
  const Components parts = components(n, triangles);
  const Eigen::MatrixX3d centroids = component_centroids(input, parts);
  const std::vector<std::vector<int>> neighbours = corner_neighbours(n, triangles);

  std::vector<double> input_area(m);
  for (Eigen::Index t = 0; t < m; ++t) {
    const Eigen::Vector3d a = input.row(triangles(t, 0)), b = input.row(triangles(t, 1)), c = input.row(triangles(t, 2));
    input_area[t] = 0.5 * (b - a).cross(c - a).norm();
  }
  std::vector<Eigen::Vector3d> normal(m), smooth(m), next(m);
  std::vector<int> targets(m);
  const int threads = parallel_threads(m);
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (Eigen::Index t = 0; t < m; ++t) {
      const Eigen::Vector3d a = x.row(triangles(t, 0)), b = x.row(triangles(t, 1)), c = x.row(triangles(t, 2));
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double length = cross.norm();
      normal[t] = length > 0.0 ? Eigen::Vector3d(cross / length) : Eigen::Vector3d::Zero();
    }
    smooth = normal;
    for (int ring = 0; ring < options.rings; ++ring) {
#pragma omp parallel for num_threads(threads) schedule(static)
      for (Eigen::Index t = 0; t < m; ++t) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (int u : neighbours[t]) sum += agreement(normal[t], normal[u]) * input_area[u] * smooth[u];
        const double length = sum.norm();
        next[t] = length > 0.0 ? Eigen::Vector3d(sum / length) : smooth[t];
      }
      std::swap(smooth, next);
    }
    for (Eigen::Index t = 0; t < m; ++t) targets[t] = nearest_axis(smooth[t]);
    const Rotations rotations = fitted_rotations(input, x, triangles, weights, targets);
    const Eigen::MatrixX3d rhs = rotated_edges_rhs(input, triangles, weights, rotations) + shift * x;
    const Eigen::MatrixX3d solution = cholesky.solve(rhs);
    if (!solution.allFinite()) break;  // keep the last finite shape: it is only a guide for the labels
    x = place_components(solution, input, parts, centroids);
  }
  return x;
}

}  // namespace polycube
