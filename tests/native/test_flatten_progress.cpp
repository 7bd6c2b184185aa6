// When flattening gives up collapsing what folds (flatten_progress.h), on
// the folds real attempts left round after round.
#include <gtest/gtest.h>

#include <vector>

#include "deform/flatten_progress.h"

namespace {

using polycube::FlattenProgress;

// The round after which `progress` gives up, 0 when it never does.
int gives_up_after(FlattenProgress progress, const std::vector<int> &folds) {
  for (size_t i = 0; i < folds.size(); ++i)
    if (progress.give_up(static_cast<int>(i) + 1, folds[i])) return static_cast<int>(i) + 1;
  return 0;
}

// Fandisk refined 64 times (414,274 vertices), nearest labels: the folds
// fall to 172, then rise; the rounds from 19 on were global solves of
// seconds each, all discarded.
const std::vector<int> kFandiskX64 = {3355, 1555, 1172, 1070, 961, 928, 823, 724, 649, 644, 625, 239, 194, 181, 203,
                                      172,  209,  255,  483,  382, 218, 184, 181, 145, 149, 215, 265, 249, 334, 357};
// Fandisk refined 4 times (25,894 vertices), its first 22 rounds: 3 folds,
// then 7 (it went on to none at round 25).
const std::vector<int> kFandiskX4 = {210, 107, 92, 54, 49, 34, 25, 25, 13, 13, 10,
                                     13,  9,   9,  17, 18, 15, 10, 6,  3,  3,  7};

TEST(FlattenProgress, GivesUpOnALargeMeshOnceTheFoldsMoreThanDouble) {
  EXPECT_EQ(gives_up_after(FlattenProgress(414'274), kFandiskX64), 19);
  // Without that rule it went on until no progress for 8 rounds or the limit.
  EXPECT_EQ(gives_up_after(FlattenProgress(25'894), kFandiskX64), 0);
}

TEST(FlattenProgress, SmallMeshesKeepTheirRoundsThroughARise) {
  EXPECT_EQ(gives_up_after(FlattenProgress(25'894), kFandiskX4), 0);
  // The same folds on a large mesh: given up at the rise from 3 to 7.
  EXPECT_EQ(gives_up_after(FlattenProgress(FlattenProgress::kDivergedFrom), kFandiskX4), 22);
}

TEST(FlattenProgress, GivesUpAfterRoundsWithoutATenthFewerFolds) {
  // 100, then 95 for ever: progress last at round 1, given up at round 9.
  std::vector<int> stalled(12, 95);
  stalled[0] = 100;
  EXPECT_EQ(gives_up_after(FlattenProgress(1'000), stalled), 9);
  EXPECT_EQ(gives_up_after(FlattenProgress(1'000'000), stalled), 9);
}

TEST(FlattenProgress, NoFoldsLeftOnceIsNoScaleForTheNext) {
  // A local solve leaves none, its global check a couple: not diverging.
  EXPECT_EQ(gives_up_after(FlattenProgress(1'000'000), {40, 20, 0, 2, 0}), 0);
}

}  // namespace
