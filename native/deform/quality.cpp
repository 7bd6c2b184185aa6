#include "deform/quality.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <tuple>

#include "labels/axis.h"
#include "linear_algebra/parallel.h"
#include "linear_algebra/run_tasks.h"
#include "mesh/sort_by_vertex.h"

namespace polycube {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

Eigen::Vector3d doubled_normal(const Vertices& v, const Triangles& t, Eigen::Index f) {
  const Eigen::Vector3d a = v.row(t(f, 0)), b = v.row(t(f, 1)), c = v.row(t(f, 2));
  return (b - a).cross(c - a);
}

// The triangles' areas summed in order on one thread, however many
// measured them: the same scale on any number of cores.
double total_area(const std::vector<double>& area) {
  double total = 0.0;
  for (double a : area) total += a;
  return total;
}

}  // namespace

QualityMeasure::QualityMeasure(const Vertices& input, const Triangles& triangles, std::vector<int> triangle_labels)
    : triangles_(triangles), labels_(std::move(triangle_labels)), input_area_(triangles.rows()) {
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    input_area_[f] = 0.5 * doubled_normal(input, triangles, f).norm();
    input_total_ += input_area_[f];
  }
  // One sort of (edge, triangle) gives both the edges, each once, and the
  // runs of two that are the interior pairs.
  std::vector<std::tuple<int, int, int>> sides;
  sides.reserve(3 * static_cast<size_t>(triangles.rows()));
  for (Eigen::Index f = 0; f < triangles.rows(); ++f)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(f, k), b = triangles(f, (k + 1) % 3);
      if (a != b) sides.emplace_back(std::min(a, b), std::max(a, b), static_cast<int>(f));
    }
  sort_by_vertex(sides, static_cast<int>(input.rows()));
  for (size_t i = 0; i < sides.size();) {
    size_t j = i;
    while (j < sides.size() && std::get<0>(sides[j]) == std::get<0>(sides[i]) &&
           std::get<1>(sides[j]) == std::get<1>(sides[i]))
      ++j;
    edges_.emplace_back(std::get<0>(sides[i]), std::get<1>(sides[i]));
    if (j - i == 2 && std::get<2>(sides[i]) != std::get<2>(sides[i + 1]))
      interior_pairs_.emplace_back(std::get<2>(sides[i]), std::get<2>(sides[i + 1]));
    i = j;
  }
  input_lengths_.resize(edges_.size());
  for (size_t e = 0; e < edges_.size(); ++e)
    input_lengths_[e] = (input.row(edges_[e].first) - input.row(edges_[e].second)).norm();
  std::vector<char> degenerate(triangles.rows());
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) degenerate[f] = input_area_[f] == 0.0;
  input_folded_edges_ = folded_edges(input, degenerate);
}

int QualityMeasure::folded_edges(const Vertices& output, const std::vector<char>& collapsed) const {
  int folded = 0;
  const long pairs = static_cast<long>(interior_pairs_.size());
#pragma omp parallel for num_threads(parallel_threads(pairs)) reduction(+ : folded)
  for (long e = 0; e < pairs; ++e) {
    const auto [a, b] = interior_pairs_[e];
    if (collapsed[a] || collapsed[b]) continue;
    const Eigen::Vector3d na = doubled_normal(output, triangles_, a), nb = doubled_normal(output, triangles_, b);
    // dot of the unit normals < -0.5, without dividing by zero lengths
    folded += na.dot(nb) < -0.5 * na.norm() * nb.norm();
  }
  return folded;
}

FaceStates QualityMeasure::face_states(const Vertices& output) const {
  const Eigen::Index count = triangles_.rows();
  const int parts = loop_parts(count);
  FaceStates s;
  s.area.resize(count);
  s.deviation_deg.assign(count, 0.0);
  s.collapsed.assign(count, 0);
  s.flipped.assign(count, 0);
  run_in_parts(count, parts, [&](long begin, long end) {
    for (Eigen::Index f = begin; f < end; ++f) s.area[f] = 0.5 * doubled_normal(output, triangles_, f).norm();
  });
  const double total = total_area(s.area);
  s.scale2 = input_total_ > 0.0 && total > 0.0 ? total / input_total_ : 1.0;
  run_in_parts(count, parts, [&](long begin, long end) {
    for (Eigen::Index f = begin; f < end; ++f) update_face_state(output, f, s);
  });
  int flipped = 0;
  double max_deviation = 0.0;
  for (Eigen::Index f = 0; f < count; ++f) {
    flipped += s.flipped[f];
    max_deviation = std::max(max_deviation, s.deviation_deg[f]);
  }
  s.flipped_count = flipped;
  s.max_deviation_deg = max_deviation;
  return s;
}

void QualityMeasure::restate_moved(const Vertices& output, const std::vector<int>& moved, FaceStates& s) const {
  for (int f : moved) s.area[f] = 0.5 * doubled_normal(output, triangles_, f).norm();
  const double total = total_area(s.area);
  s.scale2 = input_total_ > 0.0 && total > 0.0 ? total / input_total_ : 1.0;
  for (int f : moved) update_face_state(output, f, s);
  const Eigen::Index count = triangles_.rows();
  int flipped = 0;
  double max_deviation = 0.0;
  for (Eigen::Index f = 0; f < count; ++f) {
    // A moved triangle's flag is the new scale's already; another's only
    // when the scale moved it across the bound.
    if (static_cast<bool>(s.collapsed[f]) != is_collapsed(s.area[f], input_area_[f], s.scale2))
      update_face_state(output, f, s);
    flipped += s.flipped[f];
    max_deviation = std::max(max_deviation, s.deviation_deg[f]);
  }
  s.flipped_count = flipped;
  s.max_deviation_deg = max_deviation;
}

void QualityMeasure::update_face_state(const Vertices& output, Eigen::Index f, FaceStates& s) const {
  const Eigen::Vector3d normal = doubled_normal(output, triangles_, f);
  const double area = 0.5 * normal.norm();
  s.area[f] = area;
  s.collapsed[f] = is_collapsed(area, input_area_[f], s.scale2);
  s.flipped[f] = 0;
  s.deviation_deg[f] = 0.0;
  if (s.collapsed[f]) return;
  const Eigen::Vector3d unit = normal / (2.0 * area);
  const Eigen::Vector3d axis = label_axis(labels_[f]);
  // atan2 of |cross| and dot keeps small angles accurate (acos loses them).
  s.deviation_deg[f] = std::atan2(unit.cross(axis).norm(), unit.dot(axis)) * kDegreesPerRadian;
  s.flipped[f] = unit.dot(axis) < 0.0;
}

double QualityMeasure::fold_flags(const Vertices& output, std::vector<char>& collapsed, std::vector<char>& flipped,
                                  std::vector<double>* areas) const {
  TriangleAreas measured;
  const double scale2 = fold_flags(output, measured, collapsed, flipped);
  if (areas) *areas = std::move(measured.area);
  return scale2;
}

double QualityMeasure::fold_flags(const Vertices& output, TriangleAreas& areas, std::vector<char>& collapsed,
                                  std::vector<char>& flipped) const {
  const Eigen::Index count = triangles_.rows();
  std::vector<double>& area = areas.area;
  std::vector<double>& along = areas.along;  // doubled normal . label axis
  area.resize(count);
  along.resize(count);
  run_in_parts(count, loop_parts(count), [&](long begin, long end) {
    for (Eigen::Index f = begin; f < end; ++f) {
      const Eigen::Vector3d normal = doubled_normal(output, triangles_, f);
      area[f] = 0.5 * normal.norm();
      along[f] = normal.dot(label_axis(labels_[f]));
    }
  });
  return flags_from(areas, total_area(area), collapsed, flipped);
}

double QualityMeasure::rescale_moved(const Vertices& output, const std::vector<int>& moved,
                                     TriangleAreas& areas) const {
  const long count_moved = static_cast<long>(moved.size());
  run_in_parts(count_moved, loop_parts(count_moved), [&](long begin, long end) {
    for (long i = begin; i < end; ++i) {
      const int f = moved[i];
      const Eigen::Vector3d normal = doubled_normal(output, triangles_, f);
      areas.area[f] = 0.5 * normal.norm();
      areas.along[f] = normal.dot(label_axis(labels_[f]));
    }
  });
  // Summed as fold_flags() sums them, so the scale is the same bit for bit.
  const double total = total_area(areas.area);
  return input_total_ > 0.0 && total > 0.0 ? total / input_total_ : 1.0;
}

double QualityMeasure::flags_from(const TriangleAreas& areas, double total, std::vector<char>& collapsed,
                                  std::vector<char>& flipped) const {
  const Eigen::Index count = triangles_.rows();
  const std::vector<double>& area = areas.area;
  const double scale2 = input_total_ > 0.0 && total > 0.0 ? total / input_total_ : 1.0;
  collapsed.resize(count);
  flipped.resize(count);
  run_in_parts(count, loop_parts(count), [&](long begin, long end) {
    for (Eigen::Index f = begin; f < end; ++f) {
      collapsed[f] = is_collapsed(area[f], input_area_[f], scale2);
      flipped[f] = !collapsed[f] && areas.along[f] < 0.0;
    }
  });
  return scale2;
}

bool QualityMeasure::folds_beyond(const Vertices& output, const std::vector<char>& before) const {
  std::vector<char> collapsed, flipped;
  fold_flags(output, collapsed, flipped);
  for (size_t f = 0; f < flipped.size(); ++f)
    if (flipped[f] && !before[f]) return true;
  return false;
}

Figures QualityMeasure::measure(const Vertices& output, bool errors) const {
  return measure(output, face_states(output), errors);
}

Figures QualityMeasure::measure(const Vertices& output, const FaceStates& s, bool errors) const {
  Figures figures;
  figures.normal_deviation_max_deg = s.max_deviation_deg;
  figures.flipped_faces = s.flipped_count;
  const Eigen::Index count = triangles_.rows();
  double weighted_deviation = 0.0, counted_area = 0.0, area_error = 0.0, collapsed_area = 0.0, nearest_max = 0.0,
         max_ratio = 0.0;
  int area_count = 0, collapsed = 0;
#pragma omp parallel for num_threads(parallel_threads(count)) \
    reduction(+ : weighted_deviation, counted_area, area_error, area_count, collapsed, collapsed_area) \
    reduction(max : nearest_max, max_ratio)
  for (Eigen::Index f = 0; f < count; ++f) {
    if (errors && input_area_[f] > 0.0) {
      const double ratio = s.area[f] / (s.scale2 * input_area_[f]);
      area_error += std::abs(ratio - 1.0);
      max_ratio = std::max(max_ratio, ratio);
      ++area_count;
    }
    if (s.collapsed[f]) {
      ++collapsed;
      collapsed_area += input_area_[f];
      continue;
    }
    weighted_deviation += s.area[f] * s.deviation_deg[f];
    counted_area += s.area[f];
    if (!errors) continue;
    const Eigen::Vector3d unit = doubled_normal(output, triangles_, f) / (2.0 * s.area[f]);
    const double largest = unit.cwiseAbs().maxCoeff();
    nearest_max = std::max(nearest_max, std::acos(std::min(1.0, largest)) * kDegreesPerRadian);
  }
  figures.collapsed_faces = collapsed;
  figures.collapsed_area = input_total_ > 0.0 ? collapsed_area / input_total_ : 0.0;
  figures.nearest_axis_deviation_max_deg = nearest_max;
  figures.folded_edges = folded_edges(output, s.collapsed);
  figures.normal_deviation_mean_deg = counted_area > 0.0 ? weighted_deviation / counted_area : 0.0;
  figures.area_error = area_count > 0 ? area_error / area_count : 0.0;
  figures.max_area_ratio = max_ratio;
  if (!errors) return figures;

  const double scale = std::sqrt(s.scale2);
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

double QualityMeasure::collapsed_area_fraction(const FaceStates& states) const {
  double collapsed = 0.0;
  for (size_t f = 0; f < input_area_.size(); ++f)
    if (states.collapsed[f]) collapsed += input_area_[f];
  return input_total_ > 0.0 ? collapsed / input_total_ : 0.0;
}

}  // namespace polycube
