#include "labels/open_caps.h"

#include <Eigen/Geometry>

#include "labels/axis.h"
#include "mesh/triangulate.h"
#include "mesh/union_find.h"

namespace polycube {

int label_open_caps(const PolygonMesh& mesh, const MeshAdjacency& adjacency, std::vector<int>& labels) {
  const int face_count = mesh.faces.count();
  // Components of faces through shared edges (roots: their lowest face).
  UnionFind parts(face_count);
  for (int e = 0; e < adjacency.edge_count(); ++e)
    for (int k = adjacency.edge_offsets[e] + 1; k < adjacency.edge_offsets[e + 1]; ++k)
      parts.join(adjacency.edge_faces[adjacency.edge_offsets[e]], adjacency.edge_faces[k]);
  std::vector<char> open(face_count, 0);
  for (int e = 0; e < adjacency.edge_count(); ++e)
    if (adjacency.faces_of_edge(e) == 1) open[parts.root(adjacency.edge_faces[adjacency.edge_offsets[e]])] = 1;
  // Per component, twice its area vector and twice its area.
  std::vector<Eigen::Vector3d> sum(face_count, Eigen::Vector3d::Zero());
  std::vector<double> area(face_count, 0.0);
  for (int f = 0; f < face_count; ++f) {
    const Eigen::Vector3d n = newell_normal(mesh.vertices, mesh.faces, f);
    sum[parts.root(f)] += n;
    area[parts.root(f)] += n.norm();
  }
  int count = 0;
  for (int f = 0; f < face_count; ++f) {
    const int root = parts.root(f);
    if (!open[root] || !(sum[root].norm() >= kCapMinFlatness * area[root]) || !(area[root] > 0.0)) continue;
    if (f == root) ++count;
    labels[f] = nearest_axis(sum[root]);
  }
  return count;
}

}  // namespace polycube
