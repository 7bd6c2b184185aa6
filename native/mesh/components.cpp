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

}  // namespace polycube
