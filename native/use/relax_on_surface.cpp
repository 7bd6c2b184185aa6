#include "use/relax_on_surface.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <array>

#include "mesh/nearest_point_weights.h"

namespace polycube {
namespace {

// Per triangle, the triangles across each of its edges (the edge opposite corner k).
using Across = std::vector<std::array<std::vector<int>, 3>>;

// The nearest point of a surface to q among the triangles reached from t0 across shared edges
// within reach of q (t0 itself always), walked breadth first.
struct Walk {
  const Vertices& surface;
  const Triangles& triangles;
  std::vector<int> seen = std::vector<int>(triangles.rows(), -1), queue = {};
  int stamp = 0;

  // The distance from q to triangle t, and the weights of its nearest point there.
  double distance(const Eigen::Vector3d& q, int t, Eigen::Vector3d& w) const {
    const Eigen::Vector3d ta = surface.row(triangles(t, 0)), tb = surface.row(triangles(t, 1)),
                          tc = surface.row(triangles(t, 2));
    w = nearest_point_weights(q, ta, tb, tc);
    return (w[0] * ta + w[1] * tb + w[2] * tc - q).norm();
  }

  SurfacePoint nearest(const Eigen::Vector3d& q, int t0, double reach, const Across& across,
                       double* found_distance = nullptr) {
    ++stamp;
    queue.assign(1, t0);
    seen[t0] = stamp;
    double best = std::numeric_limits<double>::infinity();
    SurfacePoint found{t0, Eigen::Vector3d::Constant(1.0 / 3.0)};
    for (size_t head = 0; head < queue.size() && head < 4096; ++head) {
      const int t = queue[head];
      Eigen::Vector3d w;
      const double d = distance(q, t, w);
      if (d > reach && t != t0) continue;
      if (d < best) {
        best = d;
        found = {t, w};
      }
      for (int k = 0; k < 3; ++k)
        for (int next : across[t][k])
          if (seen[next] != stamp) {
            seen[next] = stamp;
            queue.push_back(next);
          }
    }
    if (found_distance) *found_distance = best;
    return found;
  }
};

}  // namespace

Eigen::Vector3d surface_position(const Vertices& surface, const Triangles& triangles, const SurfacePoint& p) {
  Eigen::Vector3d x = Eigen::Vector3d::Zero();
  for (int k = 0; k < 3; ++k) x += p.weights[k] * surface.row(triangles(p.triangle, k)).transpose();
  return x;
}

Vertices relax_on_surface(const Vertices& surface, const Triangles& triangles,
                          const std::vector<std::vector<int>>& neighbours, int iterations,
                          std::vector<SurfacePoint>& points, const PolygonFaces& faces, double crease_degrees) {
  const int n = static_cast<int>(points.size());
  Vertices x(n, 3);
  for (int v = 0; v < n; ++v) x.row(v) = surface_position(surface, triangles, points[v]).transpose();
  if (iterations <= 0) return x;
  // Triangles across each edge (t, k: the edge opposite corner k): `smooth` none across a crease
  // (a point never walks over one, and one on a triangle touching a crease stays, so the crease and
  // its corners stay sampled as the grid carried them), `all` every one (to measure a face's sag).
  const double crease_cos = std::cos(crease_degrees * M_PI / 180.0);
  Across smooth(triangles.rows()), all(triangles.rows());
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
            all[t][k].push_back(u);
            if (normal_of(t).dot(normal_of(u)) >= crease_cos) smooth[t][k].push_back(u);
            else on_crease[edge[0]] = on_crease[edge[1]] = 1;
          }
  }
  auto near_crease = [&](int t) { return on_crease[triangles(t, 0)] || on_crease[triangles(t, 1)] || on_crease[triangles(t, 2)]; };
  Walk walk{surface, triangles};

  // The faces of each point, and how far a face sags from the surface: the largest distance of
  // its centre and its edges' midpoints to the surface, walked to from the nearest of its
  // corners' triangles (within that distance: the walk stays near the face).
  std::vector<std::vector<int>> faces_of(n);
  for (int f = 0; f < faces.count(); ++f)
    for (int k = faces.offsets[f]; k < faces.offsets[f + 1]; ++k) faces_of[faces.indices[k]].push_back(f);
  auto sag_at = [&](const Eigen::Vector3d& q, int f) {
    int from = -1;
    double reach = std::numeric_limits<double>::infinity();
    Eigen::Vector3d w;
    for (int k = faces.offsets[f]; k < faces.offsets[f + 1]; ++k) {
      const int t = points[faces.indices[k]].triangle;
      const double d = walk.distance(q, t, w);
      if (d < reach) reach = d, from = t;
    }
    double distance = 0.0;
    walk.nearest(q, from, reach, all, &distance);
    return distance;
  };
  // Per side of a face (indices into faces.indices) the sag at its midpoint, per face at its
  // centre, measured when first needed (-1 until then): a move changes only those it touches.
  std::vector<double> side_sag(faces.indices.size(), -1.0), centre_sag(faces.count(), -1.0);
  auto face_sag = [&](int f) {
    const int first = faces.offsets[f], size = faces.size(f);
    Eigen::Vector3d centre = Eigen::Vector3d::Zero();
    double worst = 0.0;
    for (int k = 0; k < size; ++k) {
      const Eigen::Vector3d a = x.row(faces.indices[first + k]), b = x.row(faces.indices[first + (k + 1) % size]);
      centre += a / size;
      if (side_sag[first + k] < 0.0) side_sag[first + k] = sag_at(0.5 * (a + b), f);
      worst = std::max(worst, side_sag[first + k]);
    }
    if (centre_sag[f] < 0.0) centre_sag[f] = sag_at(centre, f);
    return std::max(worst, centre_sag[f]);
  };
  // The sags a move of v changes: (slot, value before) in side_sag (slot >= 0) or centre_sag (-1 - f).
  std::vector<std::pair<int, double>> saved;
  auto forget_around = [&](int v) {
    saved.clear();
    for (int f : faces_of[v]) {
      const int first = faces.offsets[f], size = faces.size(f);
      for (int k = 0; k < size; ++k)
        if (faces.indices[first + k] == v || faces.indices[first + (k + 1) % size] == v) {
          saved.push_back({first + k, side_sag[first + k]});
          side_sag[first + k] = -1.0;
        }
      saved.push_back({-1 - f, centre_sag[f]});
      centre_sag[f] = -1.0;
    }
  };
  auto restore = [&]() {
    for (const auto& [slot, value] : saved) (slot >= 0 ? side_sag[slot] : centre_sag[-1 - slot]) = value;
  };
  auto longest_edge = [&](int v) {
    double longest = 0.0;
    for (int u : neighbours[v]) longest = std::max(longest, (x.row(u) - x.row(v)).norm());
    return longest;
  };

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
      // Nothing further than twice the move can be nearer than where the walk started.
      const SurfacePoint nearest = walk.nearest(p + move, t0, 2.0 * move.norm() + 1e-12, smooth);
      // A move that lets one of the point's faces sag further from the surface is not made: evening
      // the spacing out must not pull the quads off a curved part (a thin ear's rim) nor cut it short.
      if (faces_of[v].empty()) {
        points[v] = nearest;
        x.row(v) = surface_position(surface, triangles, nearest).transpose();
        continue;
      }
      double allowed = 1e-3 * longest_edge(v);
      for (int f : faces_of[v]) allowed = std::max(allowed, face_sag(f));
      const SurfacePoint was = points[v];
      points[v] = nearest;
      x.row(v) = surface_position(surface, triangles, nearest).transpose();
      forget_around(v);
      bool sags_further = false;
      for (int f : faces_of[v]) sags_further = sags_further || face_sag(f) > allowed;
      if (sags_further) {
        points[v] = was;
        x.row(v) = p.transpose();
        restore();
      }
    }
  }
  return x;
}

}  // namespace polycube
