// Which faces meet at each edge and at each vertex of a polygon mesh: the
// connectivity that charts, label validation, orientation and the automatic
// labeller walk. Built once per mesh, from the face lists alone.
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct MeshAdjacency {
  // Undirected edges, smaller vertex first. Edges joining a vertex to itself
  // (repeated corners) are left out: they separate nothing.
  std::vector<std::array<int, 2>> edges;
  // The faces using edge e are edge_faces[edge_offsets[e] .. edge_offsets[e+1]);
  // edge_forward says, for each of them, whether the face walks the edge from
  // edges[e][0] to edges[e][1] (the orientation check needs it).
  std::vector<int> edge_offsets{0};
  std::vector<int> edge_faces;
  std::vector<char> edge_forward;
  // The faces around vertex v are vertex_faces[vertex_offsets[v] .. vertex_offsets[v+1]),
  // each face once even if it repeats the vertex.
  std::vector<int> vertex_offsets{0};
  std::vector<int> vertex_faces;

  int edge_count() const { return static_cast<int>(edges.size()); }
  int faces_of_edge(int e) const { return edge_offsets[e + 1] - edge_offsets[e]; }
};

// Indices must be in range (check_input); the result is deterministic.
MeshAdjacency mesh_adjacency(const PolygonFaces& faces, int vertex_count);

// The faces sharing an edge with each face, ascending, each once.
std::vector<std::vector<int>> face_neighbours(const MeshAdjacency& adjacency, int face_count);

}  // namespace polycube
