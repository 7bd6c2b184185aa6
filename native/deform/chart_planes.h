// The exact polycube nearest to a Poisson solve: L x = b solved with every
// chart held flat on a plane perpendicular to its label's axis.
//
// Why: the paper's iteration only approaches its fixed points, and the robust
// variant's step control (fold_free_step.h) slows it further where a few
// faces are near collapse, so real models stall some degrees above the
// tolerance (fandisk 7, eight 6). A chart labelled +-X is flat when its
// vertices share one x; that is linear, so the polycube closest to the
// solve, in L's energy, is one sparse solve per axis with each chart's
// vertices merged into one unknown for that axis: A_k = P_k^T L P_k,
// A_k y = P_k^T b_k, x_k = P_k y. Every face then has its axis' normal
// exactly, points the other way (flipped) or has collapsed.
//
// Charts here are the vertex sets of the triangles whose labels share an
// axis, joined where they share a vertex: two charts of one axis that touch
// must share their plane, whatever their signs. Faces can also be collapsed
// on purpose (collapse()): their corners then share a second coordinate too,
// which puts them on a line.
#pragma once

#include <Eigen/SparseCore>
#include <array>
#include <functional>
#include <memory>
#include <vector>

#include "linear_algebra/sparse_cholesky.h"
#include "mesh/mesh.h"
#include "mesh/union_find.h"

namespace polycube {

class ChartPlanes {
 public:
  // Labels per triangle, 0..5. The planes refer to `triangles`, which must
  // outlive them.
  ChartPlanes(int vertex_count, const Triangles& triangles, const std::vector<int>& triangle_labels);

  // Makes the corners of triangle t share coordinate `axis` as well.
  void collapse(Eigen::Index t, int axis);

  // Reduces L (positive definite, e.g. with the diagonal shift of
  // deformation.h) to the flat-chart positions and factorises it, once per axis.
  // Called again after collapse() with the same L, it redoes only the axes
  // whose charts changed; at scale each ordered from the charts' own system
  // (whose unknowns its own join) rather than analysed afresh. The axes'
  // systems are independent: each on a thread of its own, the same factors
  // bit for bit as on one. Throws Error when a factorisation fails.
  void factorize(const Eigen::SparseMatrix<double>& laplacian);
  // The same for at most `at_most` of the axes to redo, the largest
  // systems first: the others stay for the next factorize(). A system
  // with few collapses is solved on its charts' factor when known, merged
  // (below), unless `merge` is false: factorised as it is, the same
  // factor bit for bit as from the start.
  void factorize(const Eigen::SparseMatrix<double>& laplacian, int at_most, bool merge = true);
  int factorizations() const { return factorizations_; }
  // Calls of solve() (three back-substitutions each, one per axis).
  int solves() const { return solves_; }
  // Another ChartPlanes of the same labels and Laplacian (its charts without
  // this one's collapses) shares `same_charts`' factors of the axes it has
  // not collapsed, and factorises the others with their orderings
  // (sparse_cholesky.h) instead of computing them again: the same factors,
  // bit for bit, for nothing or for less. Factors it has replaced are not
  // kept for this: two of one axis would be in memory at once.
  void use_chart_factors(const ChartPlanes& same_charts);
  // Takes `other`'s factors (of the same Laplacian, factorised since its
  // last collapse) for each axis on which this one has the same unknowns:
  // the same system, so the same factor bit for bit, for nothing. The axes
  // left are factorised by the next factorize(). What a polish does with
  // the planes of the run it polishes (polish_stage.h): B0's run ends on
  // the very charts the polish solves on, three factorisations of its
  // eleven. Its charts' orderings, where this one knows none, order the
  // systems here (factorize()).
  void share_factors(const ChartPlanes& other);
  // The analyses factorize() would make of the axes with no ordering yet,
  // of which only the orderings are kept: done ahead, beside other work
  // (RobustRun: the input's factorisation), they leave factorize() on the
  // same charts only the rest of the analysis (B0: an ordering of 2.7 ms
  // per axis).
  void order(const Eigen::SparseMatrix<double>& laplacian);
  // Takes the orderings `ordered` knows (of the same labels and Laplacian)
  // where this one knows none; factorize() uses each on the same charts
  // only, so the factors are those it would have made, bit for bit.
  void use_orderings(const ChartPlanes& ordered);
  // Frees the factors (shared ones stay with their other owner) until the
  // next factorize(), which redoes every axis.
  void release();
  // Minimises x^T L x / 2 - b^T x over the unknowns whose vertices all lie
  // in `region`, every other vertex held at its value in `positions` (with
  // the charts and collapses as they are now): after a few collapses the
  // rest of a large mesh barely moves, and this costs a small factorisation
  // instead of three of the whole mesh. Updates `positions`; returns false,
  // leaving it, when a collapse joined vertices outside the region that
  // stand at different values (then only a full solve can place them).
  bool solve_near(const Eigen::SparseMatrix<double>& laplacian, const Eigen::MatrixX3d& rhs,
                  const std::vector<char>& region, Vertices& positions) const;
  // Minimises x^T L x / 2 - b^T x over the positions with flat charts; `rhs`
  // is the n x 3 b. Uses the charts and collapses of the last factorize();
  // each axis's back-substitution on a thread of its own.
  Vertices solve(const Eigen::MatrixX3d& rhs) const;
  // Two solves at once, each to the bits it would have alone, reading each
  // factor once (sparse_cholesky.h); counted as two. `beside`, when given,
  // runs among the three axes' back-substitutions, on the thread the first
  // to end frees: three tasks on two cores leave one idle for a third of
  // the time.
  std::array<Vertices, 2> solve(const Eigen::MatrixX3d& first, const Eigen::MatrixX3d& second,
                                const std::function<void()>& beside = nullptr) const;
  // Per vertex, its unknown of coordinate `axis` as of the last factorize():
  // vertices that share one move together, or the charts stop being flat.
  const std::vector<int>& unknowns(int axis) const { return unknown_[axis]; }
  // The same as the planes stand now, factorised or not.
  std::vector<int> current_unknowns(int axis) const;

 private:
  int root(int axis, int v) const;
  // The analysis and factorisation of one axis's system of `m` unknowns
  // (unknown_[axis] numbered), or its merge onto the chart factor; touches
  // only that axis's members. Returns whether it factorised.
  bool factorize_axis(const Eigen::SparseMatrix<double>& laplacian, int axis, int m, bool merge);
  void join(int axis, int a, int b);
  // Per vertex, its set's unknown of `axis`: the sets numbered in the order
  // of their first vertex, so equal partitions give equal unknowns. Returns
  // how many there are.
  int number_unknowns(int axis, int n, std::vector<int>& of_root, std::vector<int>& unknown) const;
  // The axes `wanted` picks, each numbered (number_unknowns), the largest
  // system first: analysed and factorised one a thread, on two cores the
  // other two follow it on the second.
  struct NumberedAxes {
    std::vector<int> axes;
    std::array<int, 3> unknowns{};
    std::array<std::vector<int>, 3> unknown;
  };
  NumberedAxes numbered_axes(int n, const std::array<bool, 3>& wanted) const;
  // The K solves of solve(), one back-substitution per axis for all of them.
  template <int K>
  std::array<Vertices, K> solve_together(const std::array<const Eigen::MatrixX3d*, K>& rhs,
                                         const std::function<void()>& beside = nullptr) const;

  const Triangles& triangles_;
  mutable std::array<UnionFind, 3> sets_;    // per axis: vertices sharing that coordinate
  std::array<std::vector<int>, 3> unknown_;  // per axis and vertex: its unknown
  std::array<std::shared_ptr<const SparseCholesky>, 3> cholesky_;
  std::array<bool, 3> changed_ = {true, true, true};
  // Per axis, the factor of its charts' own system (no collapses) and each
  // vertex's unknown in it, while this one solves on it or may: a system
  // with a few collapses is then solved on that factor, its joins held by a
  // small dense Schur complement (Merged), instead of factorised again. The
  // same minimiser, to rounding (B0: four of its eight factorisations).
  struct ChartFactor {
    std::shared_ptr<const SparseCholesky> cholesky;
    std::vector<int> unknown;
  };
  std::array<std::shared_ptr<const ChartFactor>, 3> chart_factor_;
  struct Merged;
  std::array<std::shared_ptr<const Merged>, 3> merged_;  // null: the axis has its own factor
  // The merge of `axis`'s system of `m` unknowns onto its chart factor, or
  // null when that is not a finer system of the same charts or needs more
  // joins than pays (chart_planes.cpp).
  std::shared_ptr<const Merged> merged_onto_charts(int axis, int m) const;
  // Per axis: nothing collapsed since the construction (the charts alone),
  // and the ordering of the charts' system once known, with each vertex's
  // unknown in it: the systems with collapses, whose unknowns join the
  // charts', are ordered from it.
  std::array<bool, 3> charts_only_ = {true, true, true};
  // At scale, the whole analysis too (SparseCholesky::copy_analysis):
  // factorising the same charts again, as the first flattening and the
  // charts without collapses do, then skips it (B0 refined 64 times: 0.2
  // s per axis).
  struct ChartOrdering {
    SparseCholesky::Ordering ordering;
    std::vector<int> unknown;
    std::shared_ptr<const SparseCholesky> analysis;
  };
  // Shared by the planes that take them (a vertex's worth of memory each at
  // scale, several planes alive at once).
  std::array<std::shared_ptr<const ChartOrdering>, 3> chart_orderings_;
  int factorizations_ = 0;
  mutable int solves_ = 0;
};

}  // namespace polycube
