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

// The triangles sharing a corner with each triangle (itself included), each
// once: triangle t's are list[offsets[t]] up to list[offsets[t + 1]]. One
// array, not a vector per triangle: the smoothing walks them every ring.
struct CornerNeighbours {
  std::vector<long> offsets;
  std::vector<int> list;
};

CornerNeighbours corner_neighbours(Eigen::Index vertex_count, const Triangles& triangles) {
  const TriangleIncidence incidence(vertex_count, triangles);
  const Eigen::Index m = triangles.rows();
  std::vector<std::vector<int>> per_triangle(m);
#pragma omp parallel for num_threads(parallel_threads(m)) schedule(static)
  for (Eigen::Index t = 0; t < m; ++t) {
    std::vector<int>& list = per_triangle[t];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, k);
      list.insert(list.end(), incidence.triangles.begin() + incidence.offsets[v],
                  incidence.triangles.begin() + incidence.offsets[v + 1]);
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  CornerNeighbours neighbours;
  neighbours.offsets.resize(m + 1, 0);
  for (Eigen::Index t = 0; t < m; ++t) neighbours.offsets[t + 1] = neighbours.offsets[t] + per_triangle[t].size();
  neighbours.list.reserve(neighbours.offsets[m]);
  for (std::vector<int>& list : per_triangle) {
    neighbours.list.insert(neighbours.list.end(), list.begin(), list.end());
    std::vector<int>().swap(list);
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
  const CornerNeighbours neighbours = corner_neighbours(n, triangles);
  // Each neighbour's weight in the smoothing (area times agreement of the
  // normals), the same for every ring of an iteration.
  std::vector<double> weight(neighbours.list.size());

  std::vector<double> input_area(m);
  for (Eigen::Index t = 0; t < m; ++t) {
    const Eigen::Vector3d a = input.row(triangles(t, 0)), b = input.row(triangles(t, 1)),
                          c = input.row(triangles(t, 2));
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
#pragma omp parallel for num_threads(threads) schedule(static)
    for (Eigen::Index t = 0; t < m; ++t)
      for (long i = neighbours.offsets[t]; i < neighbours.offsets[t + 1]; ++i) {
        const int u = neighbours.list[i];
        weight[i] = agreement(normal[t], normal[u]) * input_area[u];
      }
    smooth = normal;
    for (int ring = 0; ring < options.rings; ++ring) {
#pragma omp parallel for num_threads(threads) schedule(static)
      for (Eigen::Index t = 0; t < m; ++t) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (long i = neighbours.offsets[t]; i < neighbours.offsets[t + 1]; ++i)
          sum += weight[i] * smooth[neighbours.list[i]];
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
