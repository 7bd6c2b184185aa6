#include "linear_algebra/laplacian.h"

#include <algorithm>
#include <cmath>

namespace polycube {

Laplacian::Laplacian(int vertex_count, const Triangles& triangles) {
  // Each column's entries straight into the matrix, with the slot each one
  // fills: counted, placed, then each column's few sorted by row. The same
  // pattern as setFromTriplets and the same slots as looking every entry up
  // in it, without the triplets and the lookups (B0: 1.9 -> 1.2 ms, ahead of
  // the analysis that waits for it).
  // For triangle t, the entry (t(k+1), t(k)) is slot (w, v) of the edge
  // opposite corner k+2, and (t(k+2), t(k)) slot (v, w) of the edge opposite
  // corner k+1 (slots_); -1 marks a column's diagonal.
  const Eigen::Index count = triangles.rows();
  std::vector<int> first(static_cast<size_t>(vertex_count) + 1, 0);
  for (int v = 0; v < vertex_count; ++v) ++first[v + 1];
  for (Eigen::Index t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k) first[triangles(t, k) + 1] += 2;
  for (int v = 0; v < vertex_count; ++v) first[v + 1] += first[v];
  std::vector<std::pair<int, int>> entries(first[vertex_count]);  // (row, slot) per column
  {
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int v = 0; v < vertex_count; ++v) entries[next[v]++] = {v, -1};
    for (Eigen::Index t = 0; t < count; ++t)
      for (int k = 0; k < 3; ++k) {
        const int column = triangles(t, k);
        entries[next[column]++] = {triangles(t, (k + 1) % 3), static_cast<int>(2 * (3 * t + (k + 2) % 3) + 1)};
        entries[next[column]++] = {triangles(t, (k + 2) % 3), static_cast<int>(2 * (3 * t + (k + 1) % 3))};
      }
  }
  slots_.resize(3 * static_cast<size_t>(count));
  diagonal_slots_.resize(vertex_count);
  std::vector<int> inner, outer(static_cast<size_t>(vertex_count) + 1, 0);
  inner.reserve(entries.size());
  for (int column = 0; column < vertex_count; ++column) {
    const auto begin = entries.begin() + first[column], end = entries.begin() + first[column + 1];
    std::sort(begin, end);
    for (auto e = begin; e != end; ++e) {
      if (e == begin || e->first != (e - 1)->first) inner.push_back(e->first);
      const int position = static_cast<int>(inner.size()) - 1;
      if (e->second < 0)
        diagonal_slots_[column] = position;
      else
        slots_[e->second / 2][e->second % 2] = position;
    }
    outer[column + 1] = static_cast<int>(inner.size());
  }
  matrix_.resize(vertex_count, vertex_count);
  matrix_.resizeNonZeros(static_cast<Eigen::Index>(inner.size()));
  std::copy(outer.begin(), outer.end(), matrix_.outerIndexPtr());
  std::copy(inner.begin(), inner.end(), matrix_.innerIndexPtr());
  std::fill(matrix_.valuePtr(), matrix_.valuePtr() + inner.size(), 0.0);
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
