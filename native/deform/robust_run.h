// The `robust` variant (deform.h, docs/design.md sections 2.5-2.6): the
// paper's iteration made fold-free, as a sequence of named stages over one
// state. robust_iteration() is the whole run:
//
//   fit (fit_step.h)              until the fitted shape stops moving, then
//   flatten (flatten_stage.h)     every chart flat at once; when that is kept:
//     relax (relax_stage.h)       as-rigid-as-possible inside the flat charts,
//                                 untangling collapsed slivers (untangle_step.h);
//   otherwise continuous (continuous_step.h): the paper's step, fold-free,
//                                 relabelling stalled faces and flattening again.
//
// Each stage is a function of its own, callable alone (its tests do).
#pragma once

#include <future>
#include <memory>
#include <vector>

#include "deform/chart_planes.h"
#include "deform/continuous_step.h"
#include "deform/deformation.h"
#include "deform/fold_free_step.h"

namespace polycube {

// The tag of RobustRun's constructor for a Deformation set up already.
struct Assembled {};

// Steps of a vertex are halved at most this often before it is held
// (fold_free_step.h); whole blends towards a flat shape likewise.
constexpr int kMaxHalvings = 6;
// The fitting phase ends when no vertex moves more than this fraction of the
// bounding box diagonal; relaxing ends likewise.
constexpr double kFitStepTolerance = 1e-3;

struct RobustRun {
  // Positive cotangent weights, the input's Laplacian assembled and (unless
  // the start converged already) factorised, the start's face states.
  explicit RobustRun(Deformation& deformation);
  // On a Deformation whose weights and Laplacian an earlier RobustRun set up
  // (the polish of a finished run, finished_run.h): the face states of its
  // positions alone.
  RobustRun(Deformation& deformation, const Assembled&);

  Deformation& d;
  FaceStates state;               // of d.x
  double diagonal = 0.0;          // of the input's bounding box
  ContinuousFallback continuous;  // the current mesh's Laplacian, when needed
  // The step control's triangles around each vertex on meshes of
  // kApproximateCurrentSolveFrom vertices or more, built by the first step
  // that folds (fold_free_step.h): once between flattening attempts, not
  // once a step. Freed while flattening, whose factors make the peak.
  std::optional<TriangleIncidence> step_incidence;
  // Once flat (flatten_stage): the charts and collapses, factorised.
  std::unique_ptr<ChartPlanes> planes;
  // At scale, until charts_like() takes them: the flattening's planes of
  // the charts alone, factorised (FlatCharts::charts). Freed before
  // Newton's factorisations of the whole mesh (untangle_step.h).
  std::unique_ptr<ChartPlanes> chart_factors;
  // The start labels' charts, ordered (ChartPlanes::order) beside the
  // input's factorisation, for the first flattening attempt; and, made
  // there too, the first fitting step's right-hand side.
  std::unique_ptr<ChartPlanes> ordered;
  // From a few thousand vertices, the largest of those charts' systems
  // factorised on a thread of its own while the input's factorisation and
  // the fitting run, which leave the second core idle part of the time:
  // the first flattening takes its factor (and waits for it). Joined
  // before `ordered` goes.
  std::future<void> ordered_factor;
  Eigen::MatrixX3d first_fit_rhs;
  bool relaxed = false, uncollapsed = false, untangle_tried = false;
  int flatten_attempts = 0, last_attempt = 0;

  // The polygon faces' neighbours, built on the first call: only a run that
  // stalls needs them (about 1 MiB and 2% of B0's run otherwise).
  const std::vector<std::vector<int>>& face_adjacency();
  // A fold-free step towards `target` (fold_free_step.h), put back on the
  // components' centroids, which per-vertex steps move a little.
  FoldFreeStep controlled_step(const Vertices& target);
  // The charts of the current labels without collapses, sharing the factors
  // of `same_charts` (of the same labels) it can, or those of
  // `chart_factors` when kept, and factorising the others with their
  // orderings (ChartPlanes::use_chart_factors).
  std::unique_ptr<ChartPlanes> charts_like(const ChartPlanes& same_charts);

 private:
  std::vector<std::vector<int>> adjacency_;
};

// The whole robust run on a Deformation just built with variant kRobust.
// Returns the flat charts it ended with, factorised (null when it never
// flattened or freed them): the polish of its result shares their factors
// (polish_stage.h).
std::unique_ptr<ChartPlanes> robust_iteration(Deformation& deformation);

}  // namespace polycube
