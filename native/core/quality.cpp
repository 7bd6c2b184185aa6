#include "core/quality.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "core/axis.h"
#include "core/parallel.h"

namespace polycube {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

Eigen::Vector3d triangle_normal(const Vertices& v, const Triangles& t, Eigen::Index f) {
  const Eigen::Vector3d a = v.row(t(f, 0)), b = v.row(t(f, 1)), c = v.row(t(f, 2));
  return (b - a).cross(c - a);
}

double angle_deg(const Eigen::Vector3d& unit, const Eigen::Vector3d& axis) {
  // atan2 of |cross| and dot keeps small angles accurate (acos loses them).
  return std::atan2(unit.cross(axis).norm(), unit.dot(axis)) * kDegreesPerRadian;
}

}  // namespace

QualityMeasure::QualityMeasure(const Vertices& input, const Triangles& triangles,
                               std::vector<int> triangle_labels)
    : triangles_(triangles), labels_(std::move(triangle_labels)), input_areas_(areas(input)) {
  edges_.reserve(3 * static_cast<size_t>(triangles.rows()));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(f, k), b = triangles(f, (k + 1) % 3);
      if (a != b) edges_.emplace_back(std::min(a, b), std::max(a, b));
    }
  std::sort(edges_.begin(), edges_.end());
  edges_.erase(std::unique(edges_.begin(), edges_.end()), edges_.end());
  input_lengths_.resize(edges_.size());
  for (size_t e = 0; e < edges_.size(); ++e)
    input_lengths_[e] = (input.row(edges_[e].first) - input.row(edges_[e].second)).norm();
}

QualityMeasure::Areas QualityMeasure::areas(const Vertices& v) const {
  Areas result;
  result.area.resize(triangles_.rows());
  double total = 0.0;
#pragma omp parallel for num_threads(parallel_threads(triangles_.rows())) reduction(+ : total)
  for (Eigen::Index f = 0; f < triangles_.rows(); ++f) {
    result.area[f] = 0.5 * triangle_normal(v, triangles_, f).norm();
    total += result.area[f];
  }
  result.total = total;
  return result;
}

Figures QualityMeasure::measure(const Vertices& output) const {
  Figures figures;
  const Areas out = areas(output);
  const double scale2 = input_areas_.total > 0.0 && out.total > 0.0 ? out.total / input_areas_.total : 1.0;
  const double scale = std::sqrt(scale2);

  double weighted_deviation = 0.0, counted_area = 0.0, area_error = 0.0, max_deviation = 0.0;
  int area_count = 0, collapsed = 0, flipped = 0;
#pragma omp parallel for num_threads(parallel_threads(triangles_.rows())) \
    reduction(+ : weighted_deviation, counted_area, area_error, area_count, collapsed, flipped) \
    reduction(max : max_deviation)
  for (Eigen::Index f = 0; f < triangles_.rows(); ++f) {
    const double a_in = input_areas_.area[f], a_out = out.area[f];
    if (a_in > 0.0) {
      area_error += std::abs(a_out / (scale2 * a_in) - 1.0);
      ++area_count;
    }
    if (a_out <= kCollapsedAreaRatio * scale2 * a_in || a_out == 0.0) {
      ++collapsed;
      continue;
    }
    const Eigen::Vector3d unit = triangle_normal(output, triangles_, f) / (2.0 * a_out);
    const Eigen::Vector3d axis = label_axis(labels_[f]);
    const double deviation = angle_deg(unit, axis);
    max_deviation = std::max(max_deviation, deviation);
    weighted_deviation += a_out * deviation;
    counted_area += a_out;
    if (unit.dot(axis) < 0.0) ++flipped;
  }
  figures.normal_deviation_max_deg = max_deviation;
  figures.collapsed_faces = collapsed;
  figures.flipped_faces = flipped;
  figures.normal_deviation_mean_deg = counted_area > 0.0 ? weighted_deviation / counted_area : 0.0;
  figures.area_error = area_count > 0 ? area_error / area_count : 0.0;

  double edge_error = 0.0;
  long edge_count = 0;
  const long edges = static_cast<long>(edges_.size());
#pragma omp parallel for num_threads(parallel_threads(edges)) reduction(+ : edge_error, edge_count)
  for (long e = 0; e < edges; ++e) {
    if (input_lengths_[e] <= 0.0) continue;
    const double length = (output.row(edges_[e].first) - output.row(edges_[e].second)).norm();
    edge_error += std::abs(length / (scale * input_lengths_[e]) - 1.0);
    ++edge_count;
  }
  figures.edge_error = edge_count > 0 ? edge_error / edge_count : 0.0;
  return figures;
}

}  // namespace polycube
