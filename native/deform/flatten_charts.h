// The last phase of the `robust` variant: from a shape close to the polycube,
// the exact polycube (every chart flat, chart_planes.h) without folds.
//
// The flat-chart solve is linear and knows nothing of orientation, so on real
// models it turns a few slivers over (fandisk with automatic labels: 44
// triangles, each a few hundred-thousandths of the model's area; B0 from
// its fitted shape: 4). Those are slivers near a chart boundary that the
// flat charts leave no room for; as-rigid-as-possible relaxation inside the
// flat charts does not untangle them (fandisk: 45 to 37 after 10 rounds).
// So each flipped triangle is collapsed onto a line: its corners also share
// the coordinate in which it is thinnest, and the solve is repeated until
// nothing is flipped (fandisk: 6 rounds). The price is more collapsed
// triangles than the plain `fixed` variant leaves (fandisk 165 against 61,
// 1% of the area), for a polycube that is exact and fold-free.
//
// Labels can ask for more than collapsing slivers (elephant, nearest-axis or
// automatic labels: a third of the area would collapse; bunny00: 15%): such
// a result is refused (also when the folds stop getting fewer:
// flatten_progress.h), and the caller keeps its continuous iteration. The
// staircase labels of the `eight` need 10.6%, the most of the models that
// flatten well.
#pragma once

#include <functional>
#include <memory>

#include "deform/chart_planes.h"
#include "deform/quality.h"
#include "linear_algebra/cotangent_weights.h"

namespace polycube {

struct FlatCharts {
  bool found = false;
  Vertices positions;                   // when found: every chart flat, nothing flipped
  FaceStates states;                    // of `positions`
  std::unique_ptr<ChartPlanes> planes;  // the charts and collapses, factorised, for relax_flat_charts
  int rounds = 0;                       // flat-chart solves done
  Vertices first_positions;             // of the first (global) solve: flat, nothing collapsed on purpose
  int collapsed_on_purpose = 0;         // triangles collapsed to undo a fold
  double collapsed_area = 0.0;          // share of the input's area collapsed
  // From kKeepChartFactorsFrom vertices: the first solve's planes, the
  // charts alone with their factors, which collapses replace in `planes`.
  // The charts without collapses (relax_stage.h) take them instead of
  // factorising the same systems again.
  std::unique_ptr<ChartPlanes> charts;
};

// At scale a chart system's factorisation costs more than a second (B0
// refined 64 times: 1.3-1.8 s per axis), and the same charts without
// collapses factorise again what the first solve had: keeping those
// factors (a third of a GiB per axis there) costs memory for time.
constexpr int kKeepChartFactorsFrom = 50'000;

// Puts a solve back where the mesh stands (Deformation::place: component centroids).
using Placement = std::function<Vertices(const Eigen::MatrixX3d& solution)>;

constexpr int kFlattenRounds = 30;

// A first solve that turns over more than this share of the triangles is far
// from what collapsing slivers can make exact: every such attempt measured
// was refused, after rounds of a second or two each at a million triangles
// (nearest labels, first solve: bunny00 refined 16 times 6.0%, refused
// after 4 rounds, 7 s; armadillo refined 16 times 11.7%, 2 rounds), where
// labels that flatten, or come close, turn over far less (B0 refined 64
// times 0.006%, fandisk refined 16 and 64 times 0.4%).
constexpr double kHopelessFlippedShare = 0.01;

// From `current`, with per-triangle labels 0..5 and the (shifted) Laplacian
// `laplacian` of `weights` (deformation.h). Gives up once more than
// `max_collapsed` of the input's area is collapsed; tries at most
// `max_rounds` solves. With `ordered` (ChartPlanes::order, of the same
// labels and Laplacian), its orderings spare the first solve's, and the
// factors it has made spare theirs. `give_up_hopeless`: gives up after the
// first solve too when it turns over more than kHopelessFlippedShare of
// the triangles (a caller with somewhere else to go: the coarse route's
// hand-over, Deformation::hand_over_unflat).
FlatCharts flatten_charts(const Vertices& input, const Vertices& current, const Triangles& triangles,
                          const std::vector<int>& triangle_labels, const CotangentWeights& weights,
                          const Eigen::SparseMatrix<double>& laplacian, double shift, const QualityMeasure& quality,
                          const Placement& place, double max_collapsed, int max_rounds = kFlattenRounds,
                          const ChartPlanes* ordered = nullptr, bool give_up_hopeless = false);

// One as-rigid-as-possible step inside the flat charts of `planes`: every
// triangle's input shape fitted onto its axis (fitted_rotations.h), solved
// with the charts held flat. Cuts edge and area error while the result stays
// an exact polycube.
Vertices relax_flat_charts(const Vertices& input, const Vertices& current, const Triangles& triangles,
                           const std::vector<int>& triangle_labels, const CotangentWeights& weights,
                           const Eigen::SparseMatrix<double>& laplacian, double shift, ChartPlanes& planes,
                           const Placement& place);

}  // namespace polycube
