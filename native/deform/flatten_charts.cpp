#include "deform/flatten_charts.h"

#include <algorithm>
#include <limits>

#include "deform/fitted_rotations.h"
#include "deform/flatten_progress.h"
#include "deform/rotated_edges_rhs.h"
#include "mesh/triangle_incidence.h"

namespace polycube {
namespace {

// The coordinate, other than the triangle's own axis, in which its corners
// are closest: collapsing it there moves them least.
int thinnest_axis(const Vertices& x, const Triangles& triangles, Eigen::Index t, int own_axis) {
  int best_axis = (own_axis + 1) % 3;
  double best = std::numeric_limits<double>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    if (axis == own_axis) continue;
    double lo = x(triangles(t, 0), axis), hi = lo;
    for (int k = 1; k < 3; ++k) {
      lo = std::min(lo, x(triangles(t, k), axis));
      hi = std::max(hi, x(triangles(t, k), axis));
    }
    if (hi - lo < best) {
      best = hi - lo;
      best_axis = axis;
    }
  }
  return best_axis;
}

// Local solves (ChartPlanes::solve_near) cover the flipped triangles and this
// many rings of triangles around them, doubling when a round does not reduce
// the folds.
constexpr int kRegionRings = 4;

}  // namespace

FlatCharts flatten_charts(const Vertices& input, const Vertices& current, const Triangles& triangles,
                          const std::vector<int>& triangle_labels, const CotangentWeights& weights,
                          const Eigen::SparseMatrix<double>& laplacian, double shift, const QualityMeasure& quality,
                          const Placement& place, double max_collapsed, int max_rounds, const ChartPlanes* ordered,
                          bool give_up_hopeless) {
  FlatCharts result;
  result.planes = std::make_unique<ChartPlanes>(static_cast<int>(current.rows()), triangles, triangle_labels);
  if (ordered) result.planes->use_chart_factors(*ordered);
  // As-rigid-as-possible targets rather than the paper's: fewer folds to undo
  // and lower edge error (fandisk 0.113 against 0.115, mesh_with_border
  // 0.073 against 0.075).
  const Eigen::MatrixX3d rhs = fitted_rhs(input, current, triangles, triangle_labels, weights, shift);
  const int n = static_cast<int>(current.rows());
  const TriangleIncidence incidence(n, triangles);  // to grow the region of a local solve
  std::vector<char> region(n);
  std::vector<int> moved;  // the triangles a local solve can move
  int rings = kRegionRings, previous_flipped = 0;
  bool verify = false;
  FlattenProgress progress(n);
  for (result.rounds = 1; result.rounds <= max_rounds; ++result.rounds) {
    // The first solve is global; after collapses, only their surroundings
    // move, widening when that does not help.
    bool solved = false;
    if (result.rounds > 1 && !verify) {
      if (result.states.flipped_count >= previous_flipped) rings *= 2;
      // Breadth first from the corners of the folded triangles, a ring at a time.
      std::fill(region.begin(), region.end(), 0);
      std::vector<int> frontier, next;
      for (Eigen::Index t = 0; t < triangles.rows(); ++t)
        if (result.states.flipped[t])
          for (int k = 0; k < 3; ++k)
            if (!region[triangles(t, k)]) {
              region[triangles(t, k)] = 1;
              frontier.push_back(triangles(t, k));
            }
      long size = static_cast<long>(frontier.size());
      for (int ring = 0; ring < rings && !frontier.empty(); ++ring) {
        next.clear();
        for (int v : frontier)
          for (int i = incidence.offsets[v]; i < incidence.offsets[v + 1]; ++i)
            for (int k = 0; k < 3; ++k) {
              const int w = triangles(incidence.triangles[i], k);
              if (!region[w]) {
                region[w] = 1;
                next.push_back(w);
              }
            }
        size += static_cast<long>(next.size());
        frontier.swap(next);
      }
      // A region of a good part of the mesh costs as much as a full solve.
      if (4 * size < n) solved = result.planes->solve_near(laplacian, rhs, region, result.positions);
    }
    if (!solved) {
      // The rounds that choose collapses follow their solve's folds, some
      // decided at the rounding of a near-degenerate triangle: they keep
      // their own factors, rounded as they always were (merged, the
      // anchor's automatic labels end with 15% of its area collapsed
      // instead of 0.03%). A round that verifies local solves only checks.
      result.planes->factorize(laplacian, 3, verify);
      result.positions = place(result.planes->solve(rhs));
    }
    previous_flipped = result.rounds == 1 ? std::numeric_limits<int>::max() : result.states.flipped_count;
    if (solved) {
      // A local solve moves the region's vertices alone.
      moved.clear();
      for (Eigen::Index t = 0; t < triangles.rows(); ++t)
        if (region[triangles(t, 0)] || region[triangles(t, 1)] || region[triangles(t, 2)])
          moved.push_back(static_cast<int>(t));
      quality.restate_moved(result.positions, moved, result.states);
    } else {
      result.states = quality.face_states(result.positions);
    }
    if (result.rounds == 1) {
      result.first_positions = result.positions;
      if (n >= kKeepChartFactorsFrom) {
        result.charts = std::make_unique<ChartPlanes>(n, triangles, triangle_labels);
        result.charts->use_chart_factors(*result.planes);
      }
    }
    result.collapsed_area = quality.collapsed_area_fraction(result.states);
    if (result.collapsed_area > max_collapsed) return result;
    if (give_up_hopeless && result.rounds == 1 &&
        result.states.flipped_count > kHopelessFlippedShare * static_cast<double>(triangles.rows()))
      return result;
    // When the folds stop getting fewer, the labels ask for more than slivers.
    if (progress.give_up(result.rounds, result.states.flipped_count)) return result;
    if (result.states.flipped_count == 0) {
      // A local solve is not the global one: relaxing (relax_flat_charts)
      // starts from the global solution with these collapses, which must be
      // fold-free too.
      if (solved) {
        verify = true;
        continue;
      }
      result.found = true;
      return result;
    }
    verify = false;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      if (!result.states.flipped[t]) continue;
      result.planes->collapse(t, thinnest_axis(current, triangles, t, triangle_labels[t] / 2));
      ++result.collapsed_on_purpose;
    }
  }
  result.rounds = max_rounds;
  return result;
}

Vertices relax_flat_charts(const Vertices& input, const Vertices& current, const Triangles& triangles,
                           const std::vector<int>& triangle_labels, const CotangentWeights& weights,
                           const Eigen::SparseMatrix<double>& laplacian, double shift, ChartPlanes& planes,
                           const Placement& place) {
  planes.factorize(laplacian);  // after local solves (solve_near), the collapses they added
  return place(planes.solve(fitted_rhs(input, current, triangles, triangle_labels, weights, shift)));
}

}  // namespace polycube
