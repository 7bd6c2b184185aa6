#include "deform/keep_opposites_apart.h"

#include <algorithm>
#include <array>

#include "labels/axis.h"
#include "mesh/triangulate.h"

namespace polycube {

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
          const Eigen::Vector3d normal = newell_normal(mesh.vertices, mesh.faces, f);
          to = -1;
          for (int label = 0; label < 6; ++label)
            if (!opposite_beside(f, label) &&
                (to < 0 || normal.dot(label_axis(label)) > normal.dot(label_axis(to))))
              to = label;
          if (to < 0) continue;
        }
      }
      labels[f] = to;
      changed[f] = 1;
      again = true;
    }
  }
  std::vector<int> result;
  for (int f = 0; f < faces; ++f)
    if (changed[f]) result.push_back(f);
  return result;
}

}  // namespace polycube
