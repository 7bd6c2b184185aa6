#include "use/quantise_planes.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace polycube {

double AxisGrid::to_grid(double x) const {
  if (planes.empty()) return x / h;
  if (x <= planes.front()) return steps.front() + (x - planes.front()) / h;
  if (x >= planes.back()) return steps.back() + (x - planes.back()) / h;
  const size_t i = std::upper_bound(planes.begin(), planes.end(), x) - planes.begin() - 1;
  if (x == planes[i]) return static_cast<double>(steps[i]);
  const double t = (x - planes[i]) / (planes[i + 1] - planes[i]);
  return steps[i] + t * (steps[i + 1] - steps[i]);
}

double AxisGrid::from_grid(double g) const {
  if (planes.empty()) return g * h;
  if (g <= steps.front()) return planes.front() + (g - steps.front()) * h;
  if (g >= steps.back()) return planes.back() + (g - steps.back()) * h;
  const size_t i = std::upper_bound(steps.begin(), steps.end(), g,
                                    [](double value, long step) { return value < step; }) - steps.begin() - 1;
  if (g == steps[i]) return planes[i];
  const double t = (g - steps[i]) / static_cast<double>(steps[i + 1] - steps[i]);
  return planes[i] + t * (planes[i + 1] - planes[i]);
}

AxisGrid quantise_planes(std::vector<double> coordinates, double h, double tolerance) {
  AxisGrid grid;
  grid.h = h;
  std::sort(coordinates.begin(), coordinates.end());
  for (double x : coordinates)
    if (grid.planes.empty() || x - grid.planes.back() > tolerance) grid.planes.push_back(x);
  const size_t m = grid.planes.size();
  if (m == 0) return grid;

  // Strictly increasing integers q_i nearest x_i / h in total distance: with
  // p_i = q_i - i this is an L1 isotonic regression over integers, whose
  // optimum takes values among floor / ceil of the shifted targets.
  std::vector<double> target(m);
  std::vector<long> candidates;
  for (size_t i = 0; i < m; ++i) {
    target[i] = grid.planes[i] / h - static_cast<double>(i);
    candidates.push_back(static_cast<long>(std::floor(target[i])));
    candidates.push_back(static_cast<long>(std::ceil(target[i])));
  }
  std::sort(candidates.begin(), candidates.end());
  candidates.erase(std::unique(candidates.begin(), candidates.end()), candidates.end());
  const size_t n = candidates.size();
  // cost[j]: best total for planes 0..i with p_i = candidates[j]; choice remembers the best j' <= j before.
  std::vector<double> cost(n, 0.0), next(n);
  std::vector<std::vector<int>> argmin(m, std::vector<int>(n));
  for (size_t i = 0; i < m; ++i) {
    double best = std::numeric_limits<double>::infinity();
    int best_j = 0;
    for (size_t j = 0; j < n; ++j) {
      if (cost[j] < best) {
        best = cost[j];
        best_j = static_cast<int>(j);
      }
      argmin[i][j] = best_j;
      next[j] = best + std::abs(candidates[j] - target[i]);
    }
    cost.swap(next);
  }
  int j = static_cast<int>(std::min_element(cost.begin(), cost.end()) - cost.begin());
  grid.steps.assign(m, 0);
  for (size_t i = m; i-- > 0;) {
    grid.steps[i] = candidates[j] + static_cast<long>(i);
    j = argmin[i][j];
  }
  return grid;
}

}  // namespace polycube
