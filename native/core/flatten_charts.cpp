#include "core/flatten_charts.h"

#include <algorithm>
#include <array>
#include <limits>

#include "core/fitted_rotations.h"
#include "core/rotated_edges_rhs.h"
#include "core/union_find.h"

namespace polycube {
namespace {

// The coordinate in which to collapse each flipped triangle. Flipped
// triangles of one axis that share a corner fold together (a strip of
// slivers, many rows of them on a refined mesh): each such group collapses
// along one coordinate, the one other than its axis in which its corners
// (in `x`) spread least, so that the group becomes a line rather than
// points, and moves least. -1 for triangles not flipped.
std::vector<int> collapse_axes(const Vertices& x, const Triangles& triangles, const std::vector<int>& labels,
                               const std::vector<char>& flipped) {
  const Eigen::Index count = triangles.rows();
  UnionFind groups(static_cast<int>(count));
  std::vector<std::array<int, 3>> owner(x.rows(), {-1, -1, -1});  // per vertex and axis: a flipped triangle
  for (Eigen::Index t = 0; t < count; ++t) {
    if (!flipped[t]) continue;
    const int axis = labels[t] / 2;
    for (int k = 0; k < 3; ++k) {
      int& o = owner[triangles(t, k)][axis];
      if (o < 0) o = static_cast<int>(t);
      else groups.join(static_cast<int>(t), o);
    }
  }
  std::vector<Eigen::Vector3d> lo(count, Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity()));
  std::vector<Eigen::Vector3d> hi(count, Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity()));
  for (Eigen::Index t = 0; t < count; ++t) {
    if (!flipped[t]) continue;
    const int root = groups.root(static_cast<int>(t));
    for (int k = 0; k < 3; ++k) {
      lo[root] = lo[root].cwiseMin(x.row(triangles(t, k)).transpose());
      hi[root] = hi[root].cwiseMax(x.row(triangles(t, k)).transpose());
    }
  }
  std::vector<int> axes(count, -1);
  for (Eigen::Index t = 0; t < count; ++t) {
    if (!flipped[t]) continue;
    const int root = groups.root(static_cast<int>(t));
    const int own = labels[t] / 2;
    Eigen::Vector3d spread = hi[root] - lo[root];
    spread[own] = std::numeric_limits<double>::infinity();
    spread.minCoeff(&axes[t]);
  }
  return axes;
}

Eigen::MatrixX3d fitted_rhs(const Vertices& input, const Vertices& current, const Triangles& triangles,
                            const std::vector<int>& triangle_labels, const CotangentWeights& weights, double shift) {
  return rotated_edges_rhs(input, triangles, weights,
                           fitted_rotations(input, current, triangles, weights, triangle_labels)) +
         shift * current;
}

// Local solves (ChartPlanes::solve_near) cover the flipped triangles and this
// many rings of triangles around them, doubling when a round does not reduce
// the folds.
constexpr int kRegionRings = 4;
// Progress: a fifth fewer folds than the fewest so far, at least every
// kRoundsWithoutProgress rounds.
constexpr double kProgress = 0.8;
constexpr int kRoundsWithoutProgress = 6;

}  // namespace

FlatCharts flatten_charts(const Vertices& input, const Vertices& current, const Triangles& triangles,
                          const std::vector<int>& triangle_labels, const CotangentWeights& weights,
                          const Eigen::SparseMatrix<double>& laplacian, double shift, const QualityMeasure& quality,
                          const Placement& place, int max_rounds) {
  FlatCharts result;
  result.planes = std::make_unique<ChartPlanes>(static_cast<int>(current.rows()), triangles, triangle_labels);
  // As-rigid-as-possible targets rather than the paper's: fewer folds to undo
  // and lower edge error (fandisk 0.113 against 0.115, mesh_with_border
  // 0.073 against 0.075).
  const Eigen::MatrixX3d rhs = fitted_rhs(input, current, triangles, triangle_labels, weights, shift);
  // Which triangles touch each vertex, to grow the region of a local solve.
  const int n = static_cast<int>(current.rows());
  std::vector<int> first(n + 1, 0), incident(3 * triangles.rows());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) ++first[triangles(t, k) + 1];
  for (int v = 0; v < n; ++v) first[v + 1] += first[v];
  {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t)
      for (int k = 0; k < 3; ++k) incident[next[triangles(t, k)]++] = static_cast<int>(t);
  }
  std::vector<char> region(n);
  int rings = kRegionRings, previous_flipped = 0;
  bool verify = false;
  int fewest_folds = std::numeric_limits<int>::max(), last_progress = 0;
  for (result.rounds = 1; result.rounds <= max_rounds; ++result.rounds) {
    // The first solve is global; after collapses, only their surroundings
    // move, widening when that does not help.
    bool solved = false;
    if (result.rounds > 1 && !verify) {
      if (result.states.flipped_count >= previous_flipped) rings *= 2;
      std::fill(region.begin(), region.end(), 0);
      for (Eigen::Index t = 0; t < triangles.rows(); ++t)
        if (result.states.flipped[t])
          for (int k = 0; k < 3; ++k) region[triangles(t, k)] = 1;
      for (int ring = 0; ring < rings; ++ring) {
        std::vector<char> grown = region;
        for (int v = 0; v < n; ++v)
          if (region[v])
            for (int i = first[v]; i < first[v + 1]; ++i)
              for (int k = 0; k < 3; ++k) grown[triangles(incident[i], k)] = 1;
        region = std::move(grown);
      }
      // A region of a good part of the mesh costs as much as a full solve.
      if (4 * std::count(region.begin(), region.end(), 1) < n)
        solved = result.planes->solve_near(laplacian, rhs, region, result.positions);
    }
    if (!solved) {
      result.planes->factorize(laplacian);
      result.positions = place(result.planes->solve(rhs));
    }
    previous_flipped = result.rounds == 1 ? std::numeric_limits<int>::max() : result.states.flipped_count;
    result.states = quality.face_states(result.positions);
    result.collapsed_area = quality.collapsed_area_fraction(result.states);
    if (result.collapsed_area > kMaxCollapsedAreaFraction) return result;
    // Collapsing what folds usually ends in a few rounds (fandisk: 11); when
    // the folds stop getting fewer, the labels ask for more than slivers.
    if (result.states.flipped_count < kProgress * fewest_folds) {
      fewest_folds = result.states.flipped_count;
      last_progress = result.rounds;
    } else if (result.rounds - last_progress >= kRoundsWithoutProgress) {
      return result;
    }
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
    const std::vector<int> axes = collapse_axes(current, triangles, triangle_labels, result.states.flipped);
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      if (axes[t] < 0) continue;
      result.planes->collapse(t, axes[t]);
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
