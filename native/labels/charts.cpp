#include "labels/charts.h"

#include <algorithm>
#include <map>

#include "mesh/union_find.h"

namespace polycube {

Charts charts(const MeshAdjacency& adjacency, const std::vector<int>& labels) {
  const int face_count = static_cast<int>(labels.size());
  // Roots are the lowest faces, so numbering roots in face order numbers
  // charts by their lowest face. No per-call graph is built: the repair step
  // calls this many times.
  UnionFind sets(face_count);
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    const int begin = adjacency.edge_offsets[e], end = adjacency.edge_offsets[e + 1];
    for (int i = begin; i < end; ++i)
      for (int j = i + 1; j < end; ++j) {
        const int a = adjacency.edge_faces[i], b = adjacency.edge_faces[j];
        if (labels[a] != labels[b]) continue;
        sets.join(a, b);
      }
  }
  Charts result;
  result.of_face.assign(face_count, -1);
  for (int f = 0; f < face_count; ++f) {
    const int r = sets.root(f);
    if (r == f) {
      result.of_face[f] = result.count();
      result.label.push_back(labels[f]);
      result.faces.push_back(0);
    } else {
      result.of_face[f] = result.of_face[r];
    }
    ++result.faces[result.of_face[f]];
  }
  return result;
}

std::vector<ChartBoundary> chart_boundaries(const MeshAdjacency& adjacency, const Charts& charts) {
  std::map<std::array<int, 2>, std::vector<int>> edges_of_pair;
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    const int begin = adjacency.edge_offsets[e], end = adjacency.edge_offsets[e + 1];
    for (int i = begin; i < end; ++i)
      for (int j = i + 1; j < end; ++j) {
        const int a = charts.of_face[adjacency.edge_faces[i]], b = charts.of_face[adjacency.edge_faces[j]];
        if (a == b) continue;
        std::vector<int>& edges = edges_of_pair[{std::min(a, b), std::max(a, b)}];
        if (edges.empty() || edges.back() != e) edges.push_back(e);
      }
  }
  std::vector<ChartBoundary> result;
  result.reserve(edges_of_pair.size());
  for (auto& [pair, edges] : edges_of_pair) result.push_back({pair, std::move(edges)});
  return result;
}

std::vector<int> charts_at_vertex(const MeshAdjacency& adjacency, const Charts& charts, int v) {
  std::vector<int> result;
  for (int k = adjacency.vertex_offsets[v]; k < adjacency.vertex_offsets[v + 1]; ++k)
    result.push_back(charts.of_face[adjacency.vertex_faces[k]]);
  std::sort(result.begin(), result.end());
  result.erase(std::unique(result.begin(), result.end()), result.end());
  return result;
}

std::vector<std::vector<int>> chart_faces(const Charts& charts) {
  std::vector<std::vector<int>> faces(charts.count());
  for (int f = 0; f < static_cast<int>(charts.of_face.size()); ++f) faces[charts.of_face[f]].push_back(f);
  return faces;
}

std::vector<char> charts_with_open_side(const MeshAdjacency& adjacency, const Charts& charts) {
  std::vector<char> open_side(charts.count(), 0);
  for (int e = 0; e < adjacency.edge_count(); ++e)
    if (adjacency.faces_of_edge(e) == 1) open_side[charts.of_face[adjacency.edge_faces[adjacency.edge_offsets[e]]]] = 1;
  return open_side;
}

std::vector<int> chart_band(const std::vector<std::vector<int>>& neighbours, const Charts& charts, int chart,
                            const std::vector<int>& seed, int depth) {
  std::vector<int> result;
  std::vector<char> taken(charts.of_face.size(), 0);
  for (int f : seed)
    if (charts.of_face[f] == chart && !taken[f]) {
      taken[f] = 1;
      result.push_back(f);
    }
  std::vector<int> frontier = result;
  for (int step = 1; step < depth; ++step) {
    std::vector<int> next;
    for (int f : frontier)
      for (int g : neighbours[f])
        if (charts.of_face[g] == chart && !taken[g]) {
          taken[g] = 1;
          result.push_back(g);
          next.push_back(g);
        }
    frontier = std::move(next);
  }
  std::sort(result.begin(), result.end());
  return result;
}

}  // namespace polycube
