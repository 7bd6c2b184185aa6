#include "deform/keep_opposites_apart.h"

#include <algorithm>
#include <array>

#include "labels/axis.h"
#include "mesh/triangulate.h"

namespace polycube {
namespace {

// The label nearest `normal` among those opposite none of face f's
// neighbours' labels; -1 when every label is.
int nearest_opposite_none(const std::vector<std::vector<int>>& neighbours, const std::vector<int>& labels, int f,
                          const Eigen::Vector3d& normal) {
  int to = -1;
  for (int label = 0; label < 6; ++label)
    if (!touches_opposite(neighbours, labels, f, label) &&
        (to < 0 || normal.dot(label_axis(label)) > normal.dot(label_axis(to))))
      to = label;
  return to;
}

std::vector<int> marked(const std::vector<char>& flags) {
  std::vector<int> result;
  for (size_t f = 0; f < flags.size(); ++f)
    if (flags[f]) result.push_back(static_cast<int>(f));
  return result;
}

}  // namespace

bool touches_opposite(const std::vector<std::vector<int>>& neighbours, const std::vector<int>& labels, int f,
                      int label) {
  return std::any_of(neighbours[f].begin(), neighbours[f].end(), [&](int g) { return labels[g] == (label ^ 1); });
}

std::vector<int> keep_opposites_apart(const PolygonMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                                      const std::vector<int>& given, std::vector<int>& labels) {
  const int faces = static_cast<int>(labels.size());
  const auto opposite_beside = [&](int f, int label) { return touches_opposite(neighbours, labels, f, label); };
  std::vector<char> changed(faces, 0);
  for (bool again = true; again;) {
    again = false;
    for (int f = 0; f < faces; ++f) {
      if (labels[f] == given[f] || !opposite_beside(f, labels[f])) continue;
      int to = given[f];
      if (opposite_beside(f, to)) {
        std::array<int, 6> votes{};
        for (int g : neighbours[f]) ++votes[labels[g]];
        for (int label = 0; label < 6; ++label)
          if (votes[label] > 0 && opposite_beside(f, label)) votes[label] = 0;
        to = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
        if (votes[to] == 0) {
          // Between two opposite neighbours, say: the axis nearest its normal
          // among those no neighbour is opposite.
          to = nearest_opposite_none(neighbours, labels, f, newell_normal(mesh.vertices, mesh.faces, f));
          if (to < 0) continue;
        }
      }
      labels[f] = to;
      changed[f] = 1;
      again = true;
    }
  }
  return marked(changed);
}

std::vector<int> part_opposite_neighbours(const PolygonMesh& mesh, const MeshAdjacency& adjacency,
                                          const std::vector<std::vector<int>>& neighbours, std::vector<int>& labels) {
  const int faces = static_cast<int>(labels.size());
  std::vector<Eigen::Vector3d> normal(faces);
  for (int f = 0; f < faces; ++f) normal[f] = newell_normal(mesh.vertices, mesh.faces, f).normalized();
  const auto fit = [&](int f, int label) { return normal[f].dot(label_axis(label)); };
  std::vector<char> changed(faces, 0);
  for (bool again = true; again;) {
    again = false;
    for (int e = 0; e < adjacency.edge_count(); ++e) {
      if (adjacency.faces_of_edge(e) != 2) continue;
      const int f = adjacency.edge_faces[adjacency.edge_offsets[e]];
      const int g = adjacency.edge_faces[adjacency.edge_offsets[e] + 1];
      // A fold of the input's own may stay one (the figures allow as many).
      if (labels[f] != (labels[g] ^ 1) || normal[f].dot(normal[g]) < -0.5) continue;
      const int h = fit(f, labels[f]) < fit(g, labels[g]) ? f : g;
      const int to = nearest_opposite_none(neighbours, labels, h, normal[h]);
      if (to < 0) continue;
      labels[h] = to;
      changed[h] = 1;
      again = true;
    }
  }
  return marked(changed);
}

}  // namespace polycube
