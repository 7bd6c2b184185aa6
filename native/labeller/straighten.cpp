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
// Triangles per chunk of a smoothing ring handed to a thread.
constexpr int kRingChunk = 4096;
// Agreement of two unit normals, (max(0, a.b))^4: 1 when parallel, 0.25 at
// 40 degrees, 0 from 90 degrees on.
double agreement(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const double d = std::max(0.0, a.dot(b)), d2 = d * d;
  return d2 * d2;
}

// The triangles sharing a corner with each triangle (itself included), each
// once and in ascending order, kept in one array, not a vector per triangle:
// the smoothing walks them every ring. The triangles are numbered
// breadth-first over these neighbours (`order`, `position`): a triangle's
// neighbours then lie close in memory, where the input's numbering can put
// them anywhere (bunny00 refined: a quarter of them more than 4,096
// triangles away), and each ring of the smoothing waited on memory more than
// it computed. Only where the numbers are stored changes: each sum runs over
// the same neighbours in the same order.
struct CornerNeighbours {
  std::vector<int> order;     // the triangle at each position
  std::vector<int> position;  // the position of each triangle
  // The neighbours of the triangle at position p, as positions:
  // list[offsets[p]] up to list[offsets[p + 1]].
  std::vector<long> offsets;
  std::vector<int> list;
};

CornerNeighbours corner_neighbours(Eigen::Index vertex_count, const Triangles& triangles) {
  const TriangleIncidence incidence(vertex_count, triangles);
  const Eigen::Index m = triangles.rows();
  CornerNeighbours neighbours;
  neighbours.order.reserve(m);
  neighbours.position.assign(m, -1);
  for (Eigen::Index start = 0; start < m; ++start) {
    if (neighbours.position[start] >= 0) continue;
    neighbours.position[start] = static_cast<int>(neighbours.order.size());
    neighbours.order.push_back(static_cast<int>(start));
    for (size_t next = neighbours.order.size() - 1; next < neighbours.order.size(); ++next) {
      const int t = neighbours.order[next];
      for (int k = 0; k < 3; ++k) {
        const int v = triangles(t, k);
        for (int i = incidence.offsets[v]; i < incidence.offsets[v + 1]; ++i) {
          const int u = incidence.triangles[i];
          if (neighbours.position[u] >= 0) continue;
          neighbours.position[u] = static_cast<int>(neighbours.order.size());
          neighbours.order.push_back(u);
        }
      }
    }
  }
  std::vector<std::vector<int>> per_position(m);
#pragma omp parallel for num_threads(parallel_threads(m)) schedule(static)
  for (Eigen::Index p = 0; p < m; ++p) {
    std::vector<int>& list = per_position[p];
    const int t = neighbours.order[p];
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, k);
      list.insert(list.end(), incidence.triangles.begin() + incidence.offsets[v],
                  incidence.triangles.begin() + incidence.offsets[v + 1]);
    }
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    for (int& u : list) u = neighbours.position[u];
  }
  neighbours.offsets.resize(m + 1, 0);
  for (Eigen::Index p = 0; p < m; ++p) neighbours.offsets[p + 1] = neighbours.offsets[p] + per_position[p].size();
  neighbours.list.reserve(neighbours.offsets[m]);
  for (std::vector<int>& list : per_position) {
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

  // Per position of `neighbours`, not per triangle.
  std::vector<double> input_area(m);
  for (Eigen::Index p = 0; p < m; ++p) {
    const int t = neighbours.order[p];
    const Eigen::Vector3d a = input.row(triangles(t, 0)), b = input.row(triangles(t, 1)),
                          c = input.row(triangles(t, 2));
    input_area[p] = 0.5 * (b - a).cross(c - a).norm();
  }
  std::vector<Eigen::Vector3d> normal(m), smooth(m), next(m);
  std::vector<int> targets(m);
  const int threads = parallel_threads(m);
  for (int iteration = 0; iteration < options.iterations; ++iteration) {
#pragma omp parallel for num_threads(threads) schedule(static)
    for (Eigen::Index p = 0; p < m; ++p) {
      const int t = neighbours.order[p];
      const Eigen::Vector3d a = x.row(triangles(t, 0)), b = x.row(triangles(t, 1)), c = x.row(triangles(t, 2));
      const Eigen::Vector3d cross = (b - a).cross(c - a);
      const double length = cross.norm();
      normal[p] = length > 0.0 ? Eigen::Vector3d(cross / length) : Eigen::Vector3d::Zero();
    }
#pragma omp parallel for num_threads(threads) schedule(static)
    for (Eigen::Index p = 0; p < m; ++p)
      for (long i = neighbours.offsets[p]; i < neighbours.offsets[p + 1]; ++i) {
        const int q = neighbours.list[i];
        weight[i] = agreement(normal[p], normal[q]) * input_area[q];
      }
    smooth = normal;
    // In chunks handed out as threads come free, not halves fixed up front:
    // a ring takes milliseconds, and on a busy machine a thread the system
    // descheduled would hold the other one at the end of every ring.
    for (int ring = 0; ring < options.rings; ++ring) {
#pragma omp parallel for num_threads(threads) schedule(dynamic, kRingChunk)
      for (Eigen::Index p = 0; p < m; ++p) {
        Eigen::Vector3d sum = Eigen::Vector3d::Zero();
        for (long i = neighbours.offsets[p]; i < neighbours.offsets[p + 1]; ++i)
          sum += weight[i] * smooth[neighbours.list[i]];
        const double length = sum.norm();
        next[p] = length > 0.0 ? Eigen::Vector3d(sum / length) : smooth[p];
      }
      std::swap(smooth, next);
    }
    for (Eigen::Index p = 0; p < m; ++p) targets[neighbours.order[p]] = nearest_axis(smooth[p]);
    const Rotations rotations = fitted_rotations(input, x, triangles, weights, targets);
    const Eigen::MatrixX3d rhs = rotated_edges_rhs(input, triangles, weights, rotations) + shift * x;
    const Eigen::MatrixX3d solution = cholesky.solve(rhs);
    if (!solution.allFinite()) break;  // keep the last finite shape: it is only a guide for the labels
    x = place_components(solution, input, parts, centroids);
  }
  return x;
}

}  // namespace polycube
