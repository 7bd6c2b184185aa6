#include "deform/snap_to_charts.h"

#include <algorithm>
#include <vector>

namespace polycube {

Vertices snap_to_charts(const Vertices& x, const ChartPlanes& planes) {
  Vertices snapped = x;
  const int n = static_cast<int>(x.rows());
  for (int axis = 0; axis < 3; ++axis) {
    const std::vector<int> unknown = planes.current_unknowns(axis);
    const int count = unknown.empty() ? 0 : *std::max_element(unknown.begin(), unknown.end()) + 1;
    // The vertices of each unknown, grouped by a counting sort.
    std::vector<int> first(count + 1, 0), members(n);
    for (int v = 0; v < n; ++v) ++first[unknown[v] + 1];
    for (int u = 0; u < count; ++u) first[u + 1] += first[u];
    std::vector<int> next(first.begin(), first.end() - 1);
    for (int v = 0; v < n; ++v) members[next[unknown[v]]++] = v;
    std::vector<double> values;
    for (int u = 0; u < count; ++u) {
      const int size = first[u + 1] - first[u];
      if (size < 2) continue;
      values.resize(size);
      for (int i = 0; i < size; ++i) values[i] = x(members[first[u] + i], axis);
      std::nth_element(values.begin(), values.begin() + size / 2, values.end());
      const double median = values[size / 2];
      for (int i = first[u]; i < first[u + 1]; ++i) snapped(members[i], axis) = median;
    }
  }
  return snapped;
}

}  // namespace polycube
