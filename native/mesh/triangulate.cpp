#include "mesh/triangulate.h"

#include <Eigen/Geometry>

namespace polycube {

Eigen::Vector3d newell_normal(const Vertices& vertices, const PolygonFaces& faces, int face) {
  Eigen::Vector3d normal = Eigen::Vector3d::Zero();
  const int begin = faces.offsets[face], size = faces.size(face);
  for (int k = 0; k < size; ++k) {
    const Eigen::Vector3d a = vertices.row(faces.indices[begin + k]);
    const Eigen::Vector3d b = vertices.row(faces.indices[begin + (k + 1) % size]);
    normal += a.cross(b);
  }
  return normal;
}

namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); }

bool inside_triangle(const Eigen::Vector2d& p, const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                     const Eigen::Vector2d& c) {
  return cross2(b - a, p - a) >= 0 && cross2(c - b, p - b) >= 0 && cross2(a - c, p - c) >= 0;
}

// Ear clipping of one polygon, counter-clockwise in its projection. Returns
// false when no ear is found (self-intersecting or degenerate outline).
bool ear_clip(const std::vector<Eigen::Vector2d>& points, const std::vector<int>& corners,
              std::vector<Eigen::Vector3i>& out) {
  std::vector<int> ring(points.size());
  for (size_t k = 0; k < ring.size(); ++k) ring[k] = static_cast<int>(k);
  std::vector<Eigen::Vector3i> ears;
  while (ring.size() > 3) {
    const size_t m = ring.size();
    bool clipped = false;
    for (size_t k = 0; k < m && !clipped; ++k) {
      const int i0 = ring[(k + m - 1) % m], i1 = ring[k], i2 = ring[(k + 1) % m];
      const Eigen::Vector2d &a = points[i0], &b = points[i1], &c = points[i2];
      if (cross2(b - a, c - b) <= 0) continue;  // reflex or flat corner
      bool empty = true;
      for (size_t j = 0; j < m && empty; ++j) {
        const int q = ring[j];
        if (q == i0 || q == i1 || q == i2) continue;
        empty = !inside_triangle(points[q], a, b, c);
      }
      if (!empty) continue;
      ears.emplace_back(corners[i0], corners[i1], corners[i2]);
      ring.erase(ring.begin() + static_cast<long>(k));
      clipped = true;
    }
    if (!clipped) return false;
  }
  ears.emplace_back(corners[ring[0]], corners[ring[1]], corners[ring[2]]);
  out.insert(out.end(), ears.begin(), ears.end());
  return true;
}

void triangulate_polygon(const Vertices& vertices, const PolygonFaces& faces, int face,
                         std::vector<Eigen::Vector3i>& out) {
  const int begin = faces.offsets[face], size = faces.size(face);
  std::vector<int> corners(faces.indices.begin() + begin, faces.indices.begin() + begin + size);
  const Eigen::Vector3d normal = newell_normal(vertices, faces, face);
  const double length = normal.norm();
  if (length > 0) {
    // Project onto the plane of the normal with (u, v, normal) right-handed, so
    // the outline is counter-clockwise in (u, v).
    const Eigen::Vector3d n = normal / length;
    const Eigen::Vector3d u = (std::abs(n.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY())
                                  .cross(n)
                                  .normalized();
    const Eigen::Vector3d v = n.cross(u);
    std::vector<Eigen::Vector2d> points(size);
    for (int k = 0; k < size; ++k) {
      const Eigen::Vector3d p = vertices.row(corners[k]);
      points[k] = Eigen::Vector2d(p.dot(u), p.dot(v));
    }
    if (ear_clip(points, corners, out)) return;
  }
  for (int k = 1; k + 1 < size; ++k) out.emplace_back(corners[0], corners[k], corners[k + 1]);
}

}  // namespace

Triangulation triangulate(const Vertices& vertices, const PolygonFaces& faces) {
  std::vector<Eigen::Vector3i> triangles;
  std::vector<int> face_of_triangle;
  triangles.reserve(faces.indices.size());
  face_of_triangle.reserve(faces.indices.size());
  for (int f = 0; f < faces.count(); ++f) {
    if (faces.size(f) == 3) {
      const int b = faces.offsets[f];
      triangles.emplace_back(faces.indices[b], faces.indices[b + 1], faces.indices[b + 2]);
    } else {
      triangulate_polygon(vertices, faces, f, triangles);
    }
    face_of_triangle.resize(triangles.size(), f);
  }
  Triangulation result;
  result.triangles.resize(static_cast<Eigen::Index>(triangles.size()), 3);
  for (size_t t = 0; t < triangles.size(); ++t) result.triangles.row(static_cast<Eigen::Index>(t)) = triangles[t];
  result.face_of_triangle = std::move(face_of_triangle);
  return result;
}

}  // namespace polycube
