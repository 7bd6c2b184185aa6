#include "mesh/components.h"

#include "mesh/union_find.h"

namespace polycube {
Components components(int vertex_count, const Triangles& triangles) {
  UnionFind sets(vertex_count);
  std::vector<bool> used(vertex_count, false);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      used[triangles(t, k)] = true;
      sets.join(triangles(t, k), triangles(t, (k + 1) % 3));
    }
  }
  Components result;
  result.of_vertex.assign(vertex_count, -1);
  std::vector<int> id_of_root(vertex_count, -1);
  for (int v = 0; v < vertex_count; ++v) {
    if (!used[v]) continue;
    const int root = sets.root(v);
    if (id_of_root[root] < 0) id_of_root[root] = result.count++;
    result.of_vertex[v] = id_of_root[root];
  }
  return result;
}

Eigen::MatrixX3d component_centroids(const Vertices& x, const Components& components) {
  Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(components.count, 3);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(components.count);
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const int c = components.of_vertex[v];
    if (c < 0) continue;
    sum.row(c) += x.row(v);
    count[c] += 1.0;
  }
  for (int c = 0; c < components.count; ++c) sum.row(c) /= count[c];
  return sum;
}

Vertices place_components(const Eigen::MatrixX3d& solution, const Vertices& rest, const Components& components,
                          const Eigen::MatrixX3d& centroids) {
  const Eigen::MatrixX3d drift = component_centroids(solution, components) - centroids;
  Vertices y(solution.rows(), 3);
  for (Eigen::Index v = 0; v < solution.rows(); ++v) {
    const int c = components.of_vertex[v];
    y.row(v) = c < 0 ? Eigen::RowVector3d(rest.row(v)) : Eigen::RowVector3d(solution.row(v) - drift.row(c));
  }
  return y;
}

}  // namespace polycube
