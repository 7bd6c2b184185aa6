#include "deform/relabel_collapsed_faces.h"

#include <algorithm>
#include <array>
#include <utility>

#include "deform/keep_opposites_apart.h"

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
      // Not back to back with a neighbour: the edge between two faces of
      // opposite labels folds unless one of them stays collapsed.
      for (int g : neighbours[f]) votes[labels[g] ^ 1] = 0;
      const int best = static_cast<int>(std::max_element(votes.begin(), votes.end()) - votes.begin());
      if (votes[best] > 0) moves.emplace_back(f, best);
    }
    int made = 0;
    for (const auto& move : moves) {
      const int face = move.first, label = move.second;
      // Nor with a neighbour relabelled earlier in this sweep.
      if (touches_opposite(neighbours, labels, face, label)) continue;
      labels[face] = label;
      waiting[face] = 0;
      changed.push_back(face);
      ++made;
    }
    if (made == 0) break;
  }
  std::sort(changed.begin(), changed.end());
  return changed;
}

}  // namespace polycube
