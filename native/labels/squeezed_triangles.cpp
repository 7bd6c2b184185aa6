#include "labels/squeezed_triangles.h"

#include <map>

#include "mesh/triangle_incidence.h"
#include "mesh/union_find.h"

namespace polycube {

std::array<std::vector<int>, 3> axis_planes(int vertex_count, const Triangles& triangles,
                                            const std::vector<int>& triangle_labels) {
  std::array<std::vector<int>, 3> planes;
  for (int axis = 0; axis < 3; ++axis) {
    UnionFind sets(vertex_count);
    std::vector<char> on(vertex_count, 0);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      if (triangle_labels[t] < 0 || triangle_labels[t] / 2 != axis) continue;
      sets.join(triangles(t, 0), triangles(t, 1));
      sets.join(triangles(t, 0), triangles(t, 2));
      for (int k = 0; k < 3; ++k) on[triangles(t, k)] = 1;
    }
    planes[axis].resize(vertex_count);
    for (int v = 0; v < vertex_count; ++v) planes[axis][v] = on[v] ? sets.root(v) : -1;
  }
  return planes;
}

namespace {

// The axis whose plane holds all three corners of t, other than t's own; -1 when none.
int squeezing_axis(const std::array<std::vector<int>, 3>& planes, const Triangles& triangles, Eigen::Index t,
                   int label) {
  for (int axis = 0; axis < 3; ++axis) {
    if (label < 0 || axis == label / 2) continue;
    const std::vector<int>& plane = planes[axis];
    const int p = plane[triangles(t, 0)];
    if (p >= 0 && p == plane[triangles(t, 1)] && p == plane[triangles(t, 2)]) return axis;
  }
  return -1;
}

}  // namespace

std::vector<char> squeezed_triangles(int vertex_count, const Triangles& triangles,
                                     const std::vector<int>& triangle_labels) {
  const auto planes = axis_planes(vertex_count, triangles, triangle_labels);
  std::vector<char> squeezed(triangles.rows(), 0);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    squeezed[t] = squeezing_axis(planes, triangles, t, triangle_labels[t]) >= 0;
  return squeezed;
}

int unsqueeze_labels(int vertex_count, const Triangles& triangles, const std::vector<int>& face_of_triangle,
                     std::vector<int>& labels, int max_rounds) {
  const TriangleIncidence incidence(vertex_count, triangles);
  std::vector<int> triangle_labels(triangles.rows());
  std::vector<char> changed_face(labels.size(), 0);
  // The planes of a labeling (triangle_labels then holds it) and how many triangles they squeeze.
  auto planes_of = [&](const std::vector<int>& face_labels) {
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) triangle_labels[t] = face_labels[face_of_triangle[t]];
    return axis_planes(vertex_count, triangles, triangle_labels);
  };
  auto count_squeezed = [&](const std::array<std::vector<int>, 3>& planes) {
    int squeezed = 0;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t)
      squeezed += squeezing_axis(planes, triangles, t, triangle_labels[t]) >= 0;
    return squeezed;
  };
  auto planes = planes_of(labels);
  int squeezed = count_squeezed(planes);
  for (int round = 0; round < max_rounds && squeezed > 0; ++round) {
    // Decide every move from one state, then apply them together: the
    // result does not depend on the order of the triangles.
    std::vector<std::pair<int, int>> moves;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      const int axis = squeezing_axis(planes, triangles, t, triangle_labels[t]);
      if (axis < 0) continue;
      // Votes: each triangle of the squeezing plane, by the corners it shares with t.
      std::map<int, int> votes;
      for (int k = 0; k < 3; ++k) {
        const int v = triangles(t, k);
        for (int i = incidence.offsets[v]; i < incidence.offsets[v + 1]; ++i) {
          const int u = incidence.triangles[i];
          if (triangle_labels[u] < 0 || triangle_labels[u] / 2 != axis) continue;
          int shared = 0;
          for (int a = 0; a < 3; ++a)
            for (int b = 0; b < 3; ++b) shared += triangles(t, a) == triangles(u, b);
          votes[triangle_labels[u]] += shared;
        }
      }
      int best = -1, best_votes = 0;
      for (const auto& [label, count] : votes)
        if (count > best_votes) best = label, best_votes = count;
      if (best >= 0) moves.emplace_back(face_of_triangle[t], best);
    }
    if (moves.empty()) break;
    // A round that does not lower the count is undone, and ends the
    // relabelling: on coarse polygon meshes, where every corner of a large
    // face can lie on a chart boundary, moves would otherwise flood charts.
    std::vector<int> next = labels;
    for (const auto& [face, label] : moves) next[face] = label;
    auto next_planes = planes_of(next);
    const int next_squeezed = count_squeezed(next_planes);
    if (next_squeezed >= squeezed) break;
    for (const auto& [face, label] : moves)
      if (labels[face] != label) changed_face[face] = 1;
    labels = std::move(next);
    planes = std::move(next_planes);
    squeezed = next_squeezed;
  }
  int changed = 0;
  for (char c : changed_face) changed += c;
  return changed;
}

}  // namespace polycube
