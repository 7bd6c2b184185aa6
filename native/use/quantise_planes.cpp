#include "use/quantise_planes.h"

#include <algorithm>
#include <cmath>

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

  // Each gap between neighbouring planes to the whole number of steps nearest it in ratio
  // (a gap of g steps to floor(g) or ceil(g), whichever stretches the grid less), and at
  // least one. The gaps are what the grid's spacing on the surface follows: a gap of
  // 1.9 steps given one (to keep a plane near its absolute place) stretches its quads to
  // almost twice h, so the quads across that strip cut the surface's curves short.
  grid.steps.assign(m, 0);
  grid.steps[0] = std::lround(grid.planes[0] / h);
  for (size_t i = 1; i < m; ++i) {
    const double g = (grid.planes[i] - grid.planes[i - 1]) / h;
    const double low = std::max(1.0, std::floor(g));
    const long gap = static_cast<long>(g * g > low * (low + 1.0) ? low + 1.0 : low);
    grid.steps[i] = grid.steps[i - 1] + gap;
  }
  return grid;
}

}  // namespace polycube
