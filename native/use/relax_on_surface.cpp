#include "use/relax_on_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <array>


namespace polycube {
namespace {

// The nearest point of triangle abc to p, as barycentric weights (Ericson,
// Real-Time Collision Detection 5.1.5: by the Voronoi region p falls in).
Eigen::Vector3d nearest_weights(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                const Eigen::Vector3d& c) {
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0.0 && d2 <= 0.0) return {1.0, 0.0, 0.0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0.0 && d4 <= d3) return {0.0, 1.0, 0.0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0) {
    const double v = d1 / (d1 - d3);
    return {1.0 - v, v, 0.0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0.0 && d5 <= d6) return {0.0, 0.0, 1.0};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0) {
    const double w = d2 / (d2 - d6);
    return {1.0 - w, 0.0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0.0, 1.0 - w, w};
  }
  const double sum = va + vb + vc;
  if (!(sum > 0.0)) return {1.0, 0.0, 0.0};  // a degenerate triangle: its first corner
  return {va / sum, vb / sum, vc / sum};
}

}  // namespace

Eigen::Vector3d surface_position(const Vertices& surface, const Triangles& triangles, const SurfacePoint& p) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += p.weights[k] * surface.row(triangles(p.triangle, k)).transpose();
  return x;
}

Vertices relax_on_surface(const Vertices& surface, const Triangles& triangles,
                          const std::vector<std::vector<int>>& neighbours, int iterations,
                          std::vector<SurfacePoint>& points, double crease_degrees) {
  const int n = static_cast<int>(points.size());
  Vertices x(n, 3);
  for (int v = 0; v < n; ++v) x.row(v) = surface_position(surface, triangles, points[v]).transpose();
  if (iterations <= 0) return x;
  // Triangles across each edge (t, k: the edge opposite corner k), none across a crease: a point
  // never walks over one, and one on a triangle touching a crease stays, so the crease and its
  // corners stay sampled as the grid carried them.
  const double crease_cos = std::cos(crease_degrees * M_PI / 180.0);
  std::vector<std::array<std::vector<int>, 3>> across(triangles.rows());
  std::vector<char> on_crease(surface.rows(), 0);
  {
    std::map<std::array<int, 2>, std::vector<std::pair<int, int>>> edge_triangles;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int u = triangles(t, (k + 1) % 3), w = triangles(t, (k + 2) % 3);
        edge_triangles[{std::min(u, w), std::max(u, w)}].push_back({int(t), k});
      }
    auto normal_of = [&](int t) {
      const Eigen::Vector3d a = surface.row(triangles(t, 0)), b = surface.row(triangles(t, 1)), c = surface.row(triangles(t, 2));
      const Eigen::Vector3d n = (b - a).cross(c - a);
      return n.norm() > 0.0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::Zero();
    };
    for (const auto& [edge, sides] : edge_triangles)
      for (const auto& [t, k] : sides)
        for (const auto& [u, j] : sides)
          if (u != t) {
            if (normal_of(t).dot(normal_of(u)) >= crease_cos) across[t][k].push_back(u);
            else on_crease[edge[0]] = on_crease[edge[1]] = 1;
          }
  }
  auto near_crease = [&](int t) { return on_crease[triangles(t, 0)] || on_crease[triangles(t, 1)] || on_crease[triangles(t, 2)]; };
  std::vector<int> seen(triangles.rows(), -1), queue;
  int stamp = 0;
  for (int it = 0; it < iterations; ++it) {
    const Vertices before = x;
    for (int v = 0; v < n; ++v) {
      if (neighbours[v].empty() || near_crease(points[v].triangle)) continue;
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (int u : neighbours[v]) mean += before.row(u).transpose();
      mean /= static_cast<double>(neighbours[v].size());
      const Eigen::Vector3d p = before.row(v).transpose();
      const int t0 = points[v].triangle;
      const Eigen::Vector3d a = surface.row(triangles(t0, 0)), b = surface.row(triangles(t0, 1)),
                            c = surface.row(triangles(t0, 2));
      Eigen::Vector3d normal = (b - a).cross(c - a);
      Eigen::Vector3d move = 0.5 * (mean - p);
      if (normal.norm() > 0.0) {
        normal.normalize();
        move -= move.dot(normal) * normal;
      }
      const Eigen::Vector3d q = p + move;
      // The nearest point of the triangles within reach, walked to across shared vertices:
      // nothing further than twice the move can be nearer than where the walk started.
      const double reach = 2.0 * move.norm() + 1e-12;
      ++stamp;
      queue.assign(1, t0);
      seen[t0] = stamp;
      double best = std::numeric_limits<double>::infinity();
      SurfacePoint nearest = points[v];
      for (size_t head = 0; head < queue.size() && head < 4096; ++head) {
        const int t = queue[head];
        const Eigen::Vector3d ta = surface.row(triangles(t, 0)), tb = surface.row(triangles(t, 1)),
                              tc = surface.row(triangles(t, 2));
        const Eigen::Vector3d w = nearest_weights(q, ta, tb, tc);
        const double d = (w[0] * ta + w[1] * tb + w[2] * tc - q).norm();
        if (d > reach && t != t0) continue;
        if (d < best) {
          best = d;
          nearest = {t, w};
        }
        for (int k = 0; k < 3; ++k)
          for (int next : across[t][k])
            if (seen[next] != stamp) {
              seen[next] = stamp;
              queue.push_back(next);
            }
      }
      points[v] = nearest;
      x.row(v) = surface_position(surface, triangles, nearest).transpose();
    }
  }
  return x;
}

}  // namespace polycube
