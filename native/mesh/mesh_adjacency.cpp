#include "mesh/mesh_adjacency.h"

#include <algorithm>
#include <tuple>

#include "mesh/sort_by_vertex.h"

namespace polycube {

MeshAdjacency mesh_adjacency(const PolygonFaces& faces, int vertex_count) {
  MeshAdjacency adjacency;
  // (low, high, face, forward) for every face side, then sorted: equal edges
  // become neighbours, faces in increasing order within each edge.
  std::vector<std::tuple<int, int, int, char>> sides;
  sides.reserve(faces.indices.size());
  for (int f = 0; f < faces.count(); ++f) {
    const int begin = faces.offsets[f], size = faces.size(f);
    for (int k = 0; k < size; ++k) {
      const int a = faces.indices[begin + k], b = faces.indices[begin + (k + 1) % size];
      if (a == b) continue;
      sides.emplace_back(std::min(a, b), std::max(a, b), f, a < b ? 1 : 0);
    }
  }
  sort_by_vertex(sides, vertex_count);
  for (size_t k = 0; k < sides.size(); ++k) {
    const auto& [low, high, face, forward] = sides[k];
    if (k == 0 || std::get<0>(sides[k - 1]) != low || std::get<1>(sides[k - 1]) != high) {
      if (k > 0) adjacency.edge_offsets.push_back(static_cast<int>(adjacency.edge_faces.size()));
      adjacency.edges.push_back({low, high});
    }
    adjacency.edge_faces.push_back(face);
    adjacency.edge_forward.push_back(forward);
  }
  if (!sides.empty()) adjacency.edge_offsets.push_back(static_cast<int>(adjacency.edge_faces.size()));

  std::vector<int> count(vertex_count + 1, 0);
  for (int f = 0; f < faces.count(); ++f) {
    const int begin = faces.offsets[f], end = faces.offsets[f + 1];
    for (int k = begin; k < end; ++k)
      if (std::find(faces.indices.begin() + begin, faces.indices.begin() + k, faces.indices[k]) ==
          faces.indices.begin() + k)
        ++count[faces.indices[k] + 1];
  }
  for (int v = 0; v < vertex_count; ++v) count[v + 1] += count[v];
  adjacency.vertex_offsets = count;
  adjacency.vertex_faces.resize(count[vertex_count]);
  std::vector<int> fill(count.begin(), count.end() - 1);
  for (int f = 0; f < faces.count(); ++f) {
    const int begin = faces.offsets[f], end = faces.offsets[f + 1];
    for (int k = begin; k < end; ++k)
      if (std::find(faces.indices.begin() + begin, faces.indices.begin() + k, faces.indices[k]) ==
          faces.indices.begin() + k)
        adjacency.vertex_faces[fill[faces.indices[k]]++] = f;
  }
  return adjacency;
}

std::vector<std::vector<int>> face_neighbours(const MeshAdjacency& adjacency, int face_count) {
  std::vector<std::vector<int>> neighbours(face_count);
  for (int e = 0; e < adjacency.edge_count(); ++e)
    for (int i = adjacency.edge_offsets[e]; i < adjacency.edge_offsets[e + 1]; ++i)
      for (int j = adjacency.edge_offsets[e]; j < adjacency.edge_offsets[e + 1]; ++j)
        if (adjacency.edge_faces[i] != adjacency.edge_faces[j])
          neighbours[adjacency.edge_faces[i]].push_back(adjacency.edge_faces[j]);
  for (std::vector<int>& list : neighbours) {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
  }
  return neighbours;
}

}  // namespace polycube
