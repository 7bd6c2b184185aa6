#include "deform/relabel_stalled_faces.h"

#include <Eigen/Geometry>
#include <algorithm>

#include "labels/axis.h"

namespace polycube {

std::vector<int> relabel_stalled_faces(const Vertices& positions, const Triangulation& triangulation,
                                       const std::vector<std::vector<int>>& adjacency, const FaceStates& states,
                                       double min_deviation_deg, std::vector<int>& labels) {
  const int face_count = static_cast<int>(labels.size());
  std::vector<Eigen::Vector3d> normal(face_count, Eigen::Vector3d::Zero());
  std::vector<char> stalled(face_count, 0);
  const Triangles& t = triangulation.triangles;
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    const int f = triangulation.face_of_triangle[i];
    const Eigen::Vector3d a = positions.row(t(i, 0)), b = positions.row(t(i, 1)), c = positions.row(t(i, 2));
    normal[f] += (b - a).cross(c - a);
    if (!states.collapsed[i] && states.deviation_deg[i] > min_deviation_deg) stalled[f] = 1;
  }
  // Decide on the labels as they were, then apply, so the order of faces
  // does not matter.
  std::vector<std::pair<int, int>> changes;
  for (int f = 0; f < face_count; ++f) {
    if (!stalled[f] || !(normal[f].norm() > 0.0)) continue;
    // The neighbours' label closest to the face's normal, if it is closer
    // than the face's own.
    const Eigen::Vector3d unit = normal[f].normalized();
    int best = -1;
    double best_dot = unit.dot(label_axis(labels[f]));
    for (int g : adjacency[f]) {
      const double d = unit.dot(label_axis(labels[g]));
      if (labels[g] != labels[f] && d > best_dot) {
        best = labels[g];
        best_dot = d;
      }
    }
    if (best >= 0) changes.emplace_back(f, best);
  }
  // A polygon whose triangles do not all face the new axis would show a
  // flipped triangle: leave it.
  std::vector<char> refused(face_count, 0);
  std::vector<int> proposal(face_count, -1);
  for (const auto& [f, label] : changes) proposal[f] = label;
  for (Eigen::Index i = 0; i < t.rows(); ++i) {
    const int f = triangulation.face_of_triangle[i];
    if (proposal[f] < 0 || states.collapsed[i]) continue;
    const Eigen::Vector3d a = positions.row(t(i, 0)), b = positions.row(t(i, 1)), c = positions.row(t(i, 2));
    if (!((b - a).cross(c - a).dot(label_axis(proposal[f])) > 0.0)) refused[f] = 1;
  }
  std::vector<int> changed;
  for (const auto& [f, label] : changes) {
    if (refused[f]) continue;
    labels[f] = label;
    changed.push_back(f);
  }
  return changed;
}

}  // namespace polycube
