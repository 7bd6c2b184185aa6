#include "labels/faces_facing_away.h"

#include <Eigen/Geometry>

#include "labels/axis.h"
#include "mesh/triangulate.h"

namespace polycube {

int relabel_faces_facing_away(const PolygonMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                              std::vector<int>& labels, int max_sweeps) {
  const int face_count = mesh.faces.count();
  std::vector<Eigen::Vector3d> normals(face_count);
  for (int f = 0; f < face_count; ++f) normals[f] = newell_normal(mesh.vertices, mesh.faces, f);
  std::vector<char> changed(face_count, 0);
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    std::vector<std::pair<int, int>> moves;
    for (int f = 0; f < face_count; ++f) {
      // Zero-area faces have no direction to face away from.
      if (!(normals[f].dot(label_axis(labels[f])) < 0.0)) continue;
      int best = nearest_axis(normals[f]);
      double best_dot = 0.0;
      for (int g : neighbours[f]) {
        const double dot = normals[f].dot(label_axis(labels[g]));
        if (dot > best_dot) best = labels[g], best_dot = dot;
      }
      moves.emplace_back(f, best);
    }
    if (moves.empty()) break;
    for (const auto& [face, label] : moves) {
      labels[face] = label;
      changed[face] = 1;
    }
  }
  int count = 0;
  for (char c : changed) count += c;
  return count;
}

}  // namespace polycube
