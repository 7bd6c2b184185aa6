#include "deform/fold_free_step.h"

#include <algorithm>

namespace polycube {
namespace {

// Rounds of holding corners before the step is shortened as a whole instead.
// A still vertex beside neighbours that move the whole way can fold the next
// ring of triangles, and so on (bunny00's first step: a ring growing by ~40
// triangles a round, on and on).
constexpr int kMaxHoldRounds = 10;

std::vector<Eigen::Index> new_folds(const FaceStates& states, const FaceStates& from_states) {
  std::vector<Eigen::Index> folds;
  for (size_t t = 0; t < states.flipped.size(); ++t)
    if (states.flipped[t] && !from_states.flipped[t]) folds.push_back(static_cast<Eigen::Index>(t));
  return folds;
}

// The largest fraction 1/2, 1/4, ... of the whole step that folds nothing; the
// step is zero if none does. Trials ask only whether they fold; the one taken
// is measured in full.
void shorten_whole_step(const Vertices& from, const FaceStates& from_states, const Vertices& to,
                        const QualityMeasure& measure, std::vector<double>& alpha, FoldFreeStep& step) {
  std::fill(alpha.begin(), alpha.end(), 0.0);
  step.positions = from;
  step.states = from_states;
  for (double fraction = 0.5; fraction > 0x1p-10; fraction *= 0.5) {
    Vertices trial = from + fraction * (to - from);
    if (measure.folds_beyond(trial, from_states.flipped)) continue;
    std::fill(alpha.begin(), alpha.end(), fraction);
    step.states = measure.face_states(trial);
    step.positions = std::move(trial);
    return;
  }
}

}  // namespace

FoldFreeStep fold_free_step(const Vertices& from, const FaceStates& from_states, const Vertices& to,
                            const Triangles& triangles, const QualityMeasure& measure, int max_halvings,
                            std::optional<TriangleIncidence>* incidence) {
  const Eigen::Index n = from.rows();
  // A round re-measures only what it moved, walking the incidence. Without
  // a kept one, each step builds its own up front (as small meshes do: built
  // later, B0's peak rose by 1.3 MiB, the allocator's doing); a kept one is
  // built by the first step that folds.
  std::optional<TriangleIncidence> own_incidence;
  if (!incidence) {
    own_incidence.emplace(n, triangles);
    incidence = &own_incidence;
  }
  std::vector<double> alpha(n, 1.0);
  std::vector<int> stamp(triangles.rows(), -1);
  FoldFreeStep step;
  step.positions = to;
  step.held.assign(triangles.rows(), 0);
  int round = 0;
  // A full measurement fixes the scale s; rounds then re-measure only the
  // triangles around moved corners at that scale. The scale moves a little as
  // corners are held, so a full measurement closes the step and may reopen it.
  for (bool exact = false; !exact;) {
    step.states = measure.face_states(step.positions);
    std::vector<Eigen::Index> folds = new_folds(step.states, from_states);
    exact = folds.empty();
    while (!folds.empty()) {
      if (round++ == max_halvings + kMaxHoldRounds) {
        shorten_whole_step(from, from_states, to, measure, alpha, step);
        exact = true;
        break;
      }
      if (!*incidence) incidence->emplace(n, triangles);
      std::vector<int> moved;
      for (Eigen::Index t : folds) {
        step.held[t] = 1;
        for (int k = 0; k < 3; ++k) {
          const int v = triangles(t, k);
          alpha[v] = round <= max_halvings ? 0.5 * alpha[v] : 0.0;
          moved.push_back(v);
        }
      }
      std::sort(moved.begin(), moved.end());
      moved.erase(std::unique(moved.begin(), moved.end()), moved.end());
      folds.clear();
      for (int v : moved) {
        step.positions.row(v) = from.row(v) + alpha[v] * (to.row(v) - from.row(v));
      }
      for (int v : moved)
        for (int k = (*incidence)->offsets[v]; k < (*incidence)->offsets[v + 1]; ++k) {
          const int t = (*incidence)->triangles[k];
          if (stamp[t] == round) continue;
          stamp[t] = round;
          measure.update_face_state(step.positions, t, step.states);
          if (step.states.flipped[t] && !from_states.flipped[t]) folds.push_back(t);
        }
    }
  }
  for (Eigen::Index v = 0; v < n; ++v) step.limited += alpha[v] < 1.0;
  return step;
}

}  // namespace polycube
