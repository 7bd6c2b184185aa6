#include "deform/relabel_collapsed_faces.h"

#include <algorithm>
#include <array>
#include <utility>

namespace polycube {

std::vector<int> relabel_collapsed_faces(const std::vector<std::vector<int>>& neighbours,
                                         const std::vector<char>& collapsed, std::vector<int>& labels,
                                         int max_sweeps) {
  const int face_count = static_cast<int>(labels.size());
  std::vector<char> waiting(collapsed.begin(), collapsed.end());
  std::vector<int> changed;
  for (int sweep = 0; sweep < max_sweeps; ++sweep) {
    std::vector<std::pair<int, int>> moves;
    for (int f = 0; f < face_count; ++f) {
      if (!waiting[f]) continue;
      std::array<int, 6> votes{};
      for (int g : neighbours[f])
        if (!waiting[g] && labels[g] != labels[f] && labels[g] != (labels[f] ^ 1)) ++votes[labels[g]];
      const int best = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
      if (votes[best] > 0) moves.emplace_back(f, best);
    }
    if (moves.empty()) break;
    for (const auto& [face, label] : moves) {
      labels[face] = label;
      waiting[face] = 0;
      changed.push_back(face);
    }
  }
  std::sort(changed.begin(), changed.end());
  return changed;
}

}  // namespace polycube
