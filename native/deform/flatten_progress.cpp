#include "deform/flatten_progress.h"

namespace polycube {

bool FlattenProgress::give_up(int round, int folds) {
  if (folds < kProgress * fewest_) {
    fewest_ = folds;
    last_progress_ = round;
    return false;
  }
  // None left once (a local solve) is no scale for a global solve's few.
  return round - last_progress_ >= kRoundsWithoutProgress ||
         (diverging_counts_ && fewest_ > 0 && folds > kDiverged * fewest_);
}

}  // namespace polycube
