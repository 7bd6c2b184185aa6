#include "labels/keep_valid_moves.h"

#include <memory>

#include "labels/violation_score.h"

namespace polycube {
namespace {

// ViolationDelta scores a labeling that differs from its own on some faces by
// recounting the charts those faces touch; the moves kept since it was built
// are among them, so it is rebuilt (a whole recount) after this many, which
// keeps both the rebuilds and the recounted region small.
constexpr size_t kRebuildAfter = 32;

}  // namespace

std::vector<int> keep_valid_moves(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& edges_of_face,
                                  const std::vector<int>& labels, const std::vector<int>& moved,
                                  const std::vector<int>& changed, int* kept) {
  std::vector<int> result = labels;
  auto delta = std::make_unique<ViolationDelta>(adjacency, edges_of_face, result);
  const int limit = delta->score();
  std::vector<int> pending;  // kept since `delta` was built
  int count = 0;
  for (const int f : changed) {
    if (moved[f] == result[f]) continue;
    const int old = result[f];
    result[f] = moved[f];
    pending.push_back(f);
    if (delta->score_of(result, pending) > limit) {
      result[f] = old;
      pending.pop_back();
      continue;
    }
    ++count;
    if (pending.size() >= kRebuildAfter) {
      delta = std::make_unique<ViolationDelta>(adjacency, edges_of_face, result);
      pending.clear();
    }
  }
  if (kept) *kept = count;
  return result;
}

}  // namespace polycube
