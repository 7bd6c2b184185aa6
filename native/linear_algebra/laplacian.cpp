#include "linear_algebra/laplacian.h"

#include <algorithm>
#include <cmath>

namespace polycube {

Laplacian::Laplacian(int vertex_count, const Triangles& triangles) {
  std::vector<Eigen::Triplet<double>> pattern;
  pattern.reserve(static_cast<size_t>(vertex_count) + 6 * static_cast<size_t>(triangles.rows()));
  for (int v = 0; v < vertex_count; ++v) pattern.emplace_back(v, v, 0.0);
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, (k + 1) % 3), w = triangles(t, (k + 2) % 3);
      pattern.emplace_back(v, w, 0.0);
      pattern.emplace_back(w, v, 0.0);
    }
  }
  matrix_.resize(vertex_count, vertex_count);
  matrix_.setFromTriplets(pattern.begin(), pattern.end());
  matrix_.makeCompressed();

  // The pattern is fixed, so look each entry up once, not every assembly.
  auto slot = [&](int row, int col) {
    const int* begin = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col];
    const int* end = matrix_.innerIndexPtr() + matrix_.outerIndexPtr()[col + 1];
    return static_cast<int>(std::lower_bound(begin, end, row) - matrix_.innerIndexPtr());
  };
  diagonal_slots_.resize(vertex_count);
  for (int v = 0; v < vertex_count; ++v) diagonal_slots_[v] = slot(v, v);
  slots_.resize(3 * static_cast<size_t>(triangles.rows()));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, (k + 1) % 3), w = triangles(t, (k + 2) % 3);
      slots_[3 * t + k] = {slot(v, w), slot(w, v)};
    }
  }
}

double Laplacian::assemble(const CotangentWeights& weights, double relative_shift) {
  double* values = matrix_.valuePtr();
  std::fill(values, values + matrix_.nonZeros(), 0.0);
  const int* rows = matrix_.innerIndexPtr();
  const double* c = weights.data();  // row-major: corner k of triangle t is 3t+k, as in slots_
  for (size_t e = 0; e < slots_.size(); ++e) {
    const auto [vw, wv] = slots_[e];
    values[vw] -= c[e];
    values[wv] -= c[e];
    values[diagonal_slots_[rows[vw]]] += c[e];
    values[diagonal_slots_[rows[wv]]] += c[e];
  }
  if (relative_shift == 0.0 || diagonal_slots_.empty()) return 0.0;
  double mean = 0.0;
  for (int slot : diagonal_slots_) mean += std::abs(values[slot]);
  mean /= static_cast<double>(diagonal_slots_.size());
  const double shift = relative_shift * (mean > 0.0 ? mean : 1.0);
  for (int slot : diagonal_slots_) values[slot] += shift;
  return shift;
}

}  // namespace polycube
