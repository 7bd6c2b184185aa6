// Per-triangle versions of the figures of quality.h (same definitions: the
// scale s, the collapse threshold, deviation against the label axis), for the
// step control of the `robust` variant, which must know *which* faces a step
// folds, and for the list of faces that did not converge.
#pragma once

#include <vector>

#include "core/mesh.h"

namespace polycube {

struct FaceStates {
  std::vector<double> deviation_deg;  // 0 for collapsed triangles (their normal is noise)
  std::vector<char> collapsed;
  std::vector<char> flipped;          // non-collapsed, normal . axis < 0
  int flipped_count = 0;
  double max_deviation_deg = 0.0;
};

class FaceStateMeasure {
 public:
  FaceStateMeasure(const Vertices& input, const Triangles& triangles, const std::vector<int>& triangle_labels);
  FaceStates measure(const Vertices& output) const;
  void set_labels(const std::vector<int>& triangle_labels) { labels_ = triangle_labels; }

 private:
  Triangles triangles_;
  std::vector<int> labels_;
  std::vector<double> input_area_;
  double input_total_ = 0.0;
};

}  // namespace polycube
