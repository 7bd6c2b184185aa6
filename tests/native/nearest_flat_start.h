// A real model's first flat-chart solve (deform/flatten_charts.h) from its
// input, with every triangle labelled by the axis nearest its face's normal:
// the start tests of the flattening and of the untangling take.
#pragma once

#include <vector>

#include "deform/deform.h"
#include "deform/flatten_charts.h"
#include "deform/quality.h"
#include "labels/nearest_labels.h"
#include "linear_algebra/cotangent_weights.h"
#include "linear_algebra/laplacian.h"
#include "mesh/triangulate.h"

namespace polycube::test_meshes {

// Per triangle of `t`, its face's nearest-axis label.
inline std::vector<int> nearest_triangle_labels(const PolygonMesh& mesh, const Triangulation& t) {
  std::vector<int> labels;
  const std::vector<int> nearest = nearest_labels(mesh);
  for (Eigen::Index i = 0; i < t.triangles.rows(); ++i) labels.push_back(nearest[t.face_of_triangle[i]]);
  return labels;
}

inline FlatCharts flatten_from_input(const PolygonMesh& mesh, const Triangulation& t, const std::vector<int>& labels,
                                     const QualityMeasure& quality) {
  const CotangentWeights weights = cotangent_weights(mesh.vertices, t.triangles).cwiseMax(0.0);
  Laplacian laplacian(static_cast<int>(mesh.vertices.rows()), t.triangles);
  const double shift = laplacian.assemble(weights, 1e-8);
  return flatten_charts(
      mesh.vertices, mesh.vertices, t.triangles, labels, weights, laplacian.matrix(), shift, quality,
      [](const Eigen::MatrixX3d& y) { return y; }, DeformOptions{}.max_collapsed_share);
}

}  // namespace polycube::test_meshes
