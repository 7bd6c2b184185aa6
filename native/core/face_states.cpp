#include "core/face_states.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/axis.h"
#include "core/quality.h"

namespace polycube {
namespace {

Eigen::Vector3d doubled_normal(const Vertices& v, const Triangles& t, Eigen::Index f) {
  const Eigen::Vector3d a = v.row(t(f, 0)), b = v.row(t(f, 1)), c = v.row(t(f, 2));
  return (b - a).cross(c - a);
}

}  // namespace

FaceStateMeasure::FaceStateMeasure(const Vertices& input, const Triangles& triangles,
                                   const std::vector<int>& triangle_labels)
    : triangles_(triangles), labels_(triangle_labels), input_area_(triangles.rows()) {
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    input_area_[f] = 0.5 * doubled_normal(input, triangles, f).norm();
    input_total_ += input_area_[f];
  }
}

FaceStates FaceStateMeasure::measure(const Vertices& output) const {
  const Eigen::Index count = triangles_.rows();
  FaceStates s;
  s.deviation_deg.assign(count, 0.0);
  s.collapsed.assign(count, 0);
  s.flipped.assign(count, 0);
  std::vector<Eigen::Vector3d> normals(count);
  double total = 0.0;
  for (Eigen::Index f = 0; f < count; ++f) {
    normals[f] = doubled_normal(output, triangles_, f);
    total += 0.5 * normals[f].norm();
  }
  const double scale2 = input_total_ > 0.0 && total > 0.0 ? total / input_total_ : 1.0;
  for (Eigen::Index f = 0; f < count; ++f) {
    const double area = 0.5 * normals[f].norm();
    if (area <= kCollapsedAreaRatio * scale2 * input_area_[f] || area == 0.0) {
      s.collapsed[f] = 1;
      continue;
    }
    const Eigen::Vector3d axis = label_axis(labels_[f]);
    const Eigen::Vector3d unit = normals[f] / (2.0 * area);
    s.deviation_deg[f] = std::atan2(unit.cross(axis).norm(), unit.dot(axis)) * (180.0 / M_PI);
    s.max_deviation_deg = std::max(s.max_deviation_deg, s.deviation_deg[f]);
    if (unit.dot(axis) < 0.0) {
      s.flipped[f] = 1;
      ++s.flipped_count;
    }
  }
  return s;
}

}  // namespace polycube
