#include "core/fold_free_step.h"

#include <algorithm>

namespace polycube {
namespace {

// A triangle whose corners all stand still can still change class when the
// global scale s moves the collapse threshold (quality.h); after this many
// rounds of holding corners the step is abandoned rather than looped on.
constexpr int kMaxHoldRounds = 10;

}  // namespace

FoldFreeStep fold_free_step(const Vertices& from, const FaceStates& from_states, const Vertices& to,
                            const Triangles& triangles, const QualityMeasure& measure, int max_halvings) {
  const Eigen::Index n = from.rows();
  std::vector<double> alpha(n, 1.0);
  FoldFreeStep step;
  step.positions.resize(n, 3);
  step.held.assign(triangles.rows(), 0);
  for (int round = 0;; ++round) {
    for (Eigen::Index v = 0; v < n; ++v) step.positions.row(v) = from.row(v) + alpha[v] * (to.row(v) - from.row(v));
    step.states = measure.face_states(step.positions);
    bool folds = false;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      if (!step.states.flipped[t] || from_states.flipped[t]) continue;
      folds = true;
      step.held[t] = 1;
      for (int k = 0; k < 3; ++k) {
        double& a = alpha[triangles(t, k)];
        a = round < max_halvings ? 0.5 * a : 0.0;
      }
    }
    if (!folds) break;
    if (round == max_halvings + kMaxHoldRounds) {
      // Holding corners can cascade: a still vertex beside neighbours that
      // move the whole way folds the next ring of triangles, and so on
      // (bunny00's first step: a ring growing by ~40 triangles a round).
      // Then shorten the whole step instead, as far as it takes.
      std::fill(alpha.begin(), alpha.end(), 0.0);
      step.positions = from;
      step.states = from_states;
      for (double fraction = 0.5; fraction > 0x1p-10; fraction *= 0.5) {
        const Vertices trial = from + fraction * (to - from);
        const FaceStates states = measure.face_states(trial);
        bool trial_folds = false;
        for (Eigen::Index t = 0; t < triangles.rows() && !trial_folds; ++t)
          trial_folds = states.flipped[t] && !from_states.flipped[t];
        if (trial_folds) continue;
        std::fill(alpha.begin(), alpha.end(), fraction);
        step.positions = trial;
        step.states = states;
        break;
      }
      break;
    }
  }
  for (Eigen::Index v = 0; v < n; ++v) step.limited += alpha[v] < 1.0;
  return step;
}

}  // namespace polycube
