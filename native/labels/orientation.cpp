#include "labels/orientation.h"

#include <Eigen/Geometry>

#include "labels/axis.h"
#include "mesh/check_input.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"

namespace polycube {

std::vector<int> flip_labels(const std::vector<int>& labels) {
  std::vector<int> flipped = labels;
  for (int& label : flipped) {
    if (label < kUnlabelled || label > 5)
      throw Error("label " + std::to_string(label) + " is outside -1..5 and has no opposite");
    if (label >= 0) label ^= 1;  // 0/1, 2/3, 4/5 are the opposite pairs
  }
  return flipped;
}

Orientation orientation(const PolygonMesh& input, const std::vector<int>* labels) {
  const UnitBoxMesh unit(input);  // scale independence (unit_box.h)
  const PolygonMesh& mesh = unit.mesh();
  check_input(mesh, labels);
  const int face_count = mesh.faces.count();
  const MeshAdjacency adjacency = mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows()));
  Orientation result;

  // Propagate a flip bit over two-face edges: faces on such an edge agree when
  // they walk it opposite ways. A contradiction means no winding works.
  // Each face's links (neighbour, same direction) in edge order, in one
  // array: a list per face cost B0 20,000 allocations, a quarter of this
  // check's time (docs/design.md section 2.6, "Cost").
  std::vector<int> link_offsets(face_count + 1, 0);
  std::vector<std::pair<int, bool>> links;
  std::vector<char> open_edge(face_count, 0);
  auto two_faces = [&](int e, int& a, int& b) {
    const int begin = adjacency.edge_offsets[e];
    if (adjacency.faces_of_edge(e) != 2) return false;
    a = adjacency.edge_faces[begin], b = adjacency.edge_faces[begin + 1];
    return a != b;
  };
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    int a, b;
    if (adjacency.faces_of_edge(e) != 2) {
      for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k)
        open_edge[adjacency.edge_faces[k]] = 1;
    } else if (two_faces(e, a, b)) {
      ++link_offsets[a + 1];
      ++link_offsets[b + 1];
    }
  }
  for (int f = 0; f < face_count; ++f) link_offsets[f + 1] += link_offsets[f];
  links.resize(link_offsets[face_count]);
  {
    std::vector<int> next(link_offsets.begin(), link_offsets.end() - 1);
    for (int e = 0; e < adjacency.edge_count(); ++e) {
      int a, b;
      if (!two_faces(e, a, b)) continue;
      const int begin = adjacency.edge_offsets[e];
      const bool same = adjacency.edge_forward[begin] == adjacency.edge_forward[begin + 1];
      if (same) ++result.inconsistent_edges;
      links[next[a]++] = {b, same};
      links[next[b]++] = {a, same};
    }
  }
  result.consistent = result.inconsistent_edges == 0;

  std::vector<int> component(face_count, -1);
  std::vector<char> flip(face_count, 0);
  std::vector<int> stack;
  for (int start = 0; start < face_count; ++start) {
    if (component[start] >= 0) continue;
    const int id = result.components++;
    bool closed = true, consistent = true;
    double volume = 0.0;  // six times the signed volume, about the first vertex of the component
    const Eigen::Vector3d origin = mesh.vertices.row(mesh.faces.indices[mesh.faces.offsets[start]]);
    component[start] = id;
    stack.assign(1, start);
    while (!stack.empty()) {
      const int f = stack.back();
      stack.pop_back();
      if (open_edge[f]) closed = false;
      const int begin = mesh.faces.offsets[f], size = mesh.faces.size(f);
      for (int k = 1; k + 1 < size; ++k) {  // fan: exact for planar polygons, and the sum over a closed surface
        const Eigen::Vector3d a = mesh.vertices.row(mesh.faces.indices[begin]).transpose() - origin;
        const Eigen::Vector3d b = mesh.vertices.row(mesh.faces.indices[begin + k]).transpose() - origin;
        const Eigen::Vector3d c = mesh.vertices.row(mesh.faces.indices[begin + k + 1]).transpose() - origin;
        volume += a.dot(b.cross(c));
      }
      for (int i = link_offsets[f]; i < link_offsets[f + 1]; ++i) {
        const auto [g, same] = links[i];
        if (same) consistent = false;
        const char wanted = flip[f] ^ (same ? 1 : 0);
        if (component[g] < 0) {
          component[g] = id;
          flip[g] = wanted;
          stack.push_back(g);
        } else if (flip[g] != wanted) {
          result.orientable = false;
        }
      }
    }
    if (closed) ++result.closed_components;
    if (closed && consistent && volume < 0.0) ++result.inward_components;
  }

  if (labels) {
    double against = 0.0, total = 0.0;
    for (int f = 0; f < face_count; ++f) {
      if ((*labels)[f] < 0) continue;
      const Eigen::Vector3d n = newell_normal(mesh.vertices, mesh.faces, f);  // length: twice the area
      const double area = n.norm();
      total += area;
      if (n.dot(label_axis((*labels)[f])) < 0.0) against += area;
    }
    result.area_against_labels = total > 0.0 ? against / total : 0.0;
    result.labels_opposite = result.area_against_labels > 0.5;
  }
  return result;
}

}  // namespace polycube
