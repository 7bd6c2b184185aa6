// When flatten_charts() (flatten_charts.h) gives up collapsing what folds:
// the rule over the folds its rounds leave, apart from the solves.
//
// Collapsing what folds usually ends in a few rounds (fandisk: 11). It is
// given up when the folds stop getting fewer (kRoundsWithoutProgress rounds
// without a tenth fewer than the fewest so far) and, on large meshes, as soon
// as they diverge (more than twice the fewest): the rounds after that are
// spent in vain, and at scale they cost seconds each, global solves by then
// (the region of a local solve doubles every round without progress), while
// a refused attempt's rounds are discarded whole (its untangling starts from
// the first solve). Fandisk refined 64 times: 3,355 folds, 172 by round 16,
// 483 at round 19, then on to round 30; 61 of the attempt's 71 s after round
// 19. Not below kDivergedFrom vertices: a round costs milliseconds there,
// and the rounds after such a rise can still end fold-free (fandisk refined
// 4 times: 3 folds, then 7 at round 22, none at round 25).
//
// Inputs: the mesh's vertex count, then each round's folds in turn.
// Output: whether to stop after that round.
#pragma once

#include <limits>

namespace polycube {

class FlattenProgress {
 public:
  static constexpr double kProgress = 0.9;
  static constexpr int kRoundsWithoutProgress = 8;
  static constexpr double kDiverged = 2.0;
  static constexpr long kDivergedFrom = 50'000;

  explicit FlattenProgress(long vertices) : diverging_counts_(vertices >= kDivergedFrom) {}

  // After round `round` (1, 2, ...) left `folds` triangles turned over.
  bool give_up(int round, int folds);

 private:
  bool diverging_counts_;
  int fewest_ = std::numeric_limits<int>::max();  // the folds at the last progress
  int last_progress_ = 0;
};

}  // namespace polycube
