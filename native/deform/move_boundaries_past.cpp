#include "deform/move_boundaries_past.h"

#include <array>

namespace polycube {

int move_boundaries_past(const Triangulation& triangulation, const std::vector<std::vector<int>>& neighbours,
                         const std::vector<char>& flipped, std::vector<int>& labels) {
  std::vector<char> marked(labels.size(), 0);
  for (size_t t = 0; t < flipped.size(); ++t)
    if (flipped[t]) marked[triangulation.face_of_triangle[t]] = 1;
  std::vector<std::pair<int, int>> moves;
  for (int f = 0; f < static_cast<int>(labels.size()); ++f) {
    if (!marked[f]) continue;
    std::array<int, 6> votes{};
    for (int g : neighbours[f])
      if (labels[g] != labels[f] && labels[g] != (labels[f] ^ 1)) ++votes[labels[g]];
    int best = -1;
    for (int l = 0; l < 6; ++l)
      if (votes[l] > 0 && (best < 0 || votes[l] > votes[best])) best = l;
    if (best >= 0) moves.emplace_back(f, best);
  }
  for (const auto& [face, label] : moves) labels[face] = label;
  return static_cast<int>(moves.size());
}

}  // namespace polycube
