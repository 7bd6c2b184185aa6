#include "core/components.h"

#include <numeric>

namespace polycube {
namespace {

int find_root(std::vector<int>& parent, int v) {
  while (parent[v] != v) {
    parent[v] = parent[parent[v]];
    v = parent[v];
  }
  return v;
}

}  // namespace

Components components(int vertex_count, const Triangles& triangles) {
  std::vector<int> parent(vertex_count);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<bool> used(vertex_count, false);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      used[triangles(t, k)] = true;
      const int a = find_root(parent, triangles(t, k)), b = find_root(parent, triangles(t, (k + 1) % 3));
      if (a != b) parent[std::max(a, b)] = std::min(a, b);
    }
  }
  Components result;
  result.of_vertex.assign(vertex_count, -1);
  std::vector<int> id_of_root(vertex_count, -1);
  for (int v = 0; v < vertex_count; ++v) {
    if (!used[v]) continue;
    const int root = find_root(parent, v);
    if (id_of_root[root] < 0) id_of_root[root] = result.count++;
    result.of_vertex[v] = id_of_root[root];
  }
  return result;
}

}  // namespace polycube
