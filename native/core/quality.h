// The quality figures of DESIGN.md section 4, the same definitions for the
// stopping rule, the tests, the benchmark and the Blender panel.
//
// With s = sqrt(area_out / area_in), so that uniform scale is not error:
// - collapsed: output area below 1e-3 s^2 times the triangle's input area
//   (input triangles of zero area count as collapsed once they are flat again);
//   their normals are noise, so the two normal figures leave them out;
// - normal deviation: angle between unit normal and label axis, max and mean
//   weighted by output area, in degrees;
// - flipped: non-collapsed triangles with normal . axis < 0;
// - edge error: mean over unique edges of |len_out / (s len_in) - 1|;
// - area error: mean over triangles of |area_out / (s^2 area_in) - 1|.
// Edges and triangles with zero input size have no ratio and are left out of
// the two error means.
#pragma once

#include <vector>

#include "core/mesh.h"

namespace polycube {

constexpr double kCollapsedAreaRatio = 1e-3;

struct Figures {
  double normal_deviation_max_deg = 0.0;
  double normal_deviation_mean_deg = 0.0;
  double edge_error = 0.0;
  double area_error = 0.0;
  int flipped_faces = 0;
  int collapsed_faces = 0;
};

// Keeps what does not change between iterations (input areas, the edge list
// and input lengths) so each measurement costs one pass over the mesh.
class QualityMeasure {
 public:
  QualityMeasure(const Vertices& input, const Triangles& triangles, std::vector<int> triangle_labels);

  Figures measure(const Vertices& output) const;

 private:
  struct Areas {
    std::vector<double> area;
    double total = 0.0;
  };
  Areas areas(const Vertices& v) const;

  Triangles triangles_;
  std::vector<int> labels_;
  Areas input_areas_;
  std::vector<std::pair<int, int>> edges_;
  std::vector<double> input_lengths_;
};

}  // namespace polycube
