#include "deform/keep_opposites_apart.h"

#include <algorithm>
#include <array>

#include "labels/axis.h"
#include "mesh/triangulate.h"

namespace polycube {

std::vector<int> keep_opposites_apart(const PolygonMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                                      const std::vector<int>& given, std::vector<int>& labels) {
  const int faces = static_cast<int>(labels.size());
  const auto touches_opposite = [&](int f, int label) {
    return std::any_of(neighbours[f].begin(), neighbours[f].end(), [&](int g) { return labels[g] == (label ^ 1); });
  };
  std::vector<char> changed(faces, 0);
  for (bool again = true; again;) {
    again = false;
    for (int f = 0; f < faces; ++f) {
      if (labels[f] == given[f] || !touches_opposite(f, labels[f])) continue;
      int to = given[f];
      if (touches_opposite(f, to)) {
        std::array<int, 6> votes{};
        for (int g : neighbours[f]) ++votes[labels[g]];
        for (int label = 0; label < 6; ++label)
          if (votes[label] > 0 && touches_opposite(f, label)) votes[label] = 0;
        to = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
        if (votes[to] == 0) {
          // Between two opposite neighbours, say: the axis nearest its normal
          // among those no neighbour is opposite.
          const Eigen::Vector3d normal = newell_normal(mesh.vertices, mesh.faces, f);
          to = -1;
          for (int label = 0; label < 6; ++label)
            if (!touches_opposite(f, label) &&
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
