// The quality figures of docs/design.md section 4, the same definitions for the
// stopping rule, the step control, the tests, the benchmark and the panel.
//
// With s = sqrt(area_out / area_in), so that uniform scale is not error:
// - collapsed: output area below 1e-3 s^2 times the triangle's input area
//   (input triangles of zero area count as collapsed once they are flat again);
//   their normals are noise, so the two normal figures leave them out;
// - normal deviation: angle between unit normal and label axis, max and mean
//   weighted by output area, in degrees;
// - flipped: non-collapsed triangles with normal . axis < 0;
// - edge error: mean over unique edges of |len_out / (s len_in) - 1|;
// - area error: mean over triangles of |area_out / (s^2 area_in) - 1|;
// - largest area ratio: max over triangles of area_out / (s^2 area_in): a
//   fin (a few small triangles stretched far out of their chart) is plain
//   to see on the polycube but moves the area error only a little;
// - folded edges: edges between exactly two non-collapsed triangles whose
//   unit normals are more than 120 degrees apart (dot < -0.5); a polycube
//   has none of its own (its edges turn by 90 degrees), and it needs no
//   labels, so it also judges runs whose labels changed;
// - collapsed area: the input area of the collapsed triangles over the total;
// - nearest-axis deviation: like the normal deviation, against the axis
//   nearest each output normal (0 for any polycube, whatever its labels).
// Edges and triangles with zero input size have no ratio and are left out of
// the two error means.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

constexpr double kCollapsedAreaRatio = 1e-3;

// A face (triangle or polygon) of output area `area` is collapsed when it
// keeps no more than kCollapsedAreaRatio of its input area at the output's
// scale (`scale2`: output over input total area), or none at all.
inline bool is_collapsed(double area, double input_area, double scale2) {
  return area <= kCollapsedAreaRatio * scale2 * input_area || area == 0.0;
}

struct Figures {
  double normal_deviation_max_deg = 0.0;
  double normal_deviation_mean_deg = 0.0;
  double edge_error = 0.0;
  double area_error = 0.0;
  double max_area_ratio = 0.0;
  int flipped_faces = 0;
  int collapsed_faces = 0;
  int folded_edges = 0;
  double collapsed_area = 0.0;  // share of the input's area
  double nearest_axis_deviation_max_deg = 0.0;
};

// The same definitions per triangle: which faces a step folds (the robust
// variant's step control) and which did not converge.
struct FaceStates {
  std::vector<double> area;           // output area
  std::vector<double> deviation_deg;  // 0 for collapsed triangles (their normal is noise)
  std::vector<char> collapsed;
  std::vector<char> flipped;  // non-collapsed, normal . axis < 0
  double scale2 = 1.0;        // s^2
  int flipped_count = 0;
  double max_deviation_deg = 0.0;
};

// Per triangle, its area and its doubled normal along its label's axis:
// what QualityMeasure::fold_flags() derives its flags from.
struct TriangleAreas {
  std::vector<double> area, along;
};

// Keeps what does not change between iterations (input areas, the edge list
// and input lengths) so each measurement costs one pass over the mesh.
// It refers to `triangles`, which must outlive it (a Deformation's: a copy
// was a vertex's worth of memory at B0's peak).
class QualityMeasure {
 public:
  QualityMeasure(const Vertices& input, const Triangles& triangles, std::vector<int> triangle_labels);

  FaceStates face_states(const Vertices& output) const;
  // `states`, of positions that `output` differs from only at corners of
  // the triangles `moved`, brought to face_states(output) bit for bit: the
  // moved triangles measured again, the scale summed again, and of the
  // others only those whose collapse the new scale changes (a local solve
  // of the flattening moves a few rings around its slivers: B0 refined 64
  // times, 37 ms a round for the whole mesh).
  void restate_moved(const Vertices& output, const std::vector<int>& moved, FaceStates& states) const;
  // Re-evaluates triangle f of `states` for new positions, keeping its scale:
  // for local changes, where a full pass per change would cost O(mesh).
  // flipped_count and max_deviation_deg are not updated.
  void update_face_state(const Vertices& output, Eigen::Index f, FaceStates& states) const;
  // Whether `output` turns over a triangle not flipped in `before` (the same
  // definition as FaceStates::flipped), without the rest of the states: what
  // the step control's line search needs per trial, at a fraction of
  // face_states' cost (no angles).
  bool folds_beyond(const Vertices& output, const std::vector<char>& before) const;
  // FaceStates' `collapsed` and `flipped` alone (the same definitions), at
  // a fraction of face_states' cost: what a step control needs per trial;
  // with `areas`, each triangle's area too. Returns the scale s^2.
  double fold_flags(const Vertices& output, std::vector<char>& collapsed, std::vector<char>& flipped,
                    std::vector<double>* areas = nullptr) const;
  // The same, keeping in `areas` what the flags follow from, so that a
  // later trial that moves a few corners measures only the triangles
  // around them (rescale_moved): the polish's step control halves the
  // steps of a few unknowns per round (polish_stage.h).
  double fold_flags(const Vertices& output, TriangleAreas& areas, std::vector<char>& collapsed,
                    std::vector<char>& flipped) const;
  // The scale s^2 of `output`, whose triangles other than `moved` have the
  // corners `areas` was measured at, with the areas of `moved` brought up
  // to date: the same scale and areas as fold_flags() bit for bit, at the
  // cost of `moved` and one sum. Only a triangle of `moved` or one whose
  // area points against its axis (TriangleAreas::along) can have changed
  // flags (turned_over()).
  double rescale_moved(const Vertices& output, const std::vector<int>& moved, TriangleAreas& areas) const;
  // fold_flags()' flipped flag of triangle f from `areas` at scale `scale2`.
  bool turned_over(const TriangleAreas& areas, Eigen::Index f, double scale2) const {
    return areas.along[f] < 0.0 && !is_collapsed(areas.area[f], input_area_[f], scale2);
  }
  // Without `errors`, the edge and area error means, the largest area ratio
  // and the nearest-axis deviation are left at 0: the stopping rule needs
  // only the normal figures, and the edge pass and the nearest axes' arc
  // cosines are the costliest parts (B0: its ten iterations' measurements
  // 4.4 -> 2.0 ms).
  Figures measure(const Vertices& output, bool errors = true) const;
  // The same from `states` = face_states(output), already measured.
  Figures measure(const Vertices& output, const FaceStates& states, bool errors = true) const;

  // The share of the input's area in the collapsed triangles of `states`.
  double collapsed_area_fraction(const FaceStates& states) const;

  // The input's folded edges (no triangle of the input counts as collapsed
  // unless it has zero area): what no output may exceed.
  int input_folded_edges() const { return input_folded_edges_; }

  // What the edge and area errors are measured against: the mesh's edges
  // (vertex pairs, each once), their input lengths, the triangles' input
  // areas and the input's total area.
  const std::vector<std::pair<int, int>>& edges() const { return edges_; }
  const std::vector<double>& input_lengths() const { return input_lengths_; }
  const std::vector<double>& input_areas() const { return input_area_; }
  double input_total_area() const { return input_total_; }

  // Labels changed by a repair: the input's measurements stay.
  void set_labels(std::vector<int> triangle_labels) { labels_ = std::move(triangle_labels); }

 private:
  const Triangles& triangles_;
  std::vector<int> labels_;
  std::vector<double> input_area_;
  double input_total_ = 0.0;
  std::vector<std::pair<int, int>> edges_;
  std::vector<double> input_lengths_;
  std::vector<std::pair<int, int>> interior_pairs_;  // the two triangles of each edge that has exactly two
  int input_folded_edges_ = 0;

  int folded_edges(const Vertices& output, const std::vector<char>& collapsed) const;
  // fold_flags' flags from the areas, given their sum; returns the scale.
  double flags_from(const TriangleAreas& areas, double total, std::vector<char>& collapsed,
                    std::vector<char>& flipped) const;
};

}  // namespace polycube
