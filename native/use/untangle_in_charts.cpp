#include "use/untangle_in_charts.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

#include "deform/barrier_energy.h"
#include "linear_algebra/minimize_lbfgs.h"

namespace polycube {
namespace {

// Shape and area weigh the same in the barrier (deform/barrier_energy.h).
constexpr double kShapeAgainstArea = 0.5;

// A counted triangle: its corners, the two in-plane axes of its chart, the inverse of its
// reference edge matrix and its reference area.
struct Element {
  int corner[3];
  int b, c;
  Eigen::Matrix2d inverse;
  double area;
};

Eigen::Matrix2d edges(const Vertices& p, const Element& e) {
  Eigen::Matrix2d m;
  for (int j = 0; j < 2; ++j) {
    m(0, j) = p(e.corner[j + 1], e.b) - p(e.corner[0], e.b);
    m(1, j) = p(e.corner[j + 1], e.c) - p(e.corner[0], e.c);
  }
  return m;
}

}  // namespace

bool untangle_in_charts(const Vertices& reference, Vertices& positions, const Triangles& triangles,
                        const std::vector<int>& label, const std::vector<int>& free_axes, double min_ratio) {
  const int n = static_cast<int>(positions.rows());
  std::vector<Element> elements;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    if (label[t] < 0) continue;
    const int a = label[t] / 2;
    Element e{{triangles(t, 0), triangles(t, 1), triangles(t, 2)}, (a + 1) % 3, (a + 2) % 3, {}, 0.0};
    bool moves = false;
    for (int v : e.corner) moves |= (free_axes[v] & ((1 << e.b) | (1 << e.c))) != 0;
    if (!moves) continue;
    const Eigen::Matrix2d r = edges(reference, e);
    e.area = 0.5 * std::abs(r.determinant());
    e.inverse = r.inverse();
    elements.push_back(e);
  }
  if (elements.empty()) return true;

  // Unknowns: the free coordinates of the counted triangles' corners.
  std::vector<int> unknown(3 * static_cast<size_t>(n), -1);
  int count = 0;
  for (const Element& e : elements)
    for (int v : e.corner)
      for (int k : {e.b, e.c})
        if ((free_axes[v] & (1 << k)) && unknown[3 * v + k] < 0) unknown[3 * v + k] = count++;
  Eigen::VectorXd x(count);
  for (int v = 0; v < n; ++v)
    for (int k = 0; k < 3; ++k)
      if (unknown[3 * v + k] >= 0) x[unknown[3 * v + k]] = positions(v, k);
  auto place = [&](const Eigen::VectorXd& y) {
    for (int v = 0; v < n; ++v)
      for (int k = 0; k < 3; ++k)
        if (unknown[3 * v + k] >= 0) positions(v, k) = y[unknown[3 * v + k]];
  };
  auto smallest_ratio = [&]() {
    double smallest = INFINITY;
    for (const Element& e : elements) smallest = std::min(smallest, (edges(positions, e) * e.inverse).determinant());
    return smallest;
  };

  double eps = 1.0;
  const Objective energy = [&](const Eigen::VectorXd& y, Eigen::VectorXd& gradient) {
    place(y);
    gradient.setZero(y.size());
    double total = 0.0;
    for (const Element& e : elements) {
      Eigen::Matrix2d by_j;
      total += barrier_energy(edges(positions, e) * e.inverse, e.area, eps, kShapeAgainstArea, &by_j);
      const Eigen::Matrix2d by_edges = by_j * e.inverse.transpose();  // columns: corners 1 and 2
      const Eigen::Vector2d by_corner[3] = {-by_edges.col(0) - by_edges.col(1), by_edges.col(0), by_edges.col(1)};
      for (int q = 0; q < 3; ++q) {
        const int v = e.corner[q];
        if (unknown[3 * v + e.b] >= 0) gradient[unknown[3 * v + e.b]] += by_corner[q][0];
        if (unknown[3 * v + e.c] >= 0) gradient[unknown[3 * v + e.c]] += by_corner[q][1];
      }
    }
    return total;
  };
  // eps follows the worst triangle down (Garanzha et al.): large while some are turned over,
  // small once all are open, so the barrier then keeps them so.
  for (int round = 0; round < 8; ++round) {
    place(x);
    const double smallest = smallest_ratio();
    if (smallest > min_ratio) return true;
    eps = std::max(1e-6, std::min(eps, 2.0 * std::sqrt(std::max(0.0, -smallest) + 1e-4)));
    minimize_lbfgs(energy, x, 200, 1e-9, 1e-9);
    eps *= 0.2;
  }
  place(x);
  return smallest_ratio() > min_ratio;
}

}  // namespace polycube
