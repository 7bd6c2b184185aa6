#include "labels/keep_valid_moves.h"

#include "labels/violation_score.h"

namespace polycube {

std::vector<int> keep_valid_moves(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& edges_of_face,
                                  const std::vector<int>& labels, const std::vector<int>& moved,
                                  const std::vector<int>& changed, int* kept) {
  std::vector<int> result = labels;
  // Each kept move becomes the delta's own labels (ViolationDelta::keep_last),
  // so every move is scored on the charts around it alone.
  ViolationDelta delta(adjacency, edges_of_face, result);
  const int limit = delta.score();
  int count = 0;
  for (const int f : changed) {
    if (moved[f] == result[f]) continue;
    const int old = result[f];
    result[f] = moved[f];
    if (delta.score_of(result, {f}) > limit) {
      result[f] = old;
      continue;
    }
    delta.keep_last();
    ++count;
  }
  if (kept) *kept = count;
  return result;
}

}  // namespace polycube
