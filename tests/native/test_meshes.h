// Generated meshes for the unit tests. Real models (libcgal-demo, shared/data)
// are read from files in the tests that need them.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace polycube::test_meshes {

// A UV sphere (quads, triangle fans at the poles) scaled by `radii`.
inline PolygonMesh uv_sphere(int segments, int rings, Eigen::Vector3d radii = Eigen::Vector3d::Ones()) {
  std::vector<Eigen::Vector3d> points{{0, 0, 1}};
  for (int i = 1; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      const double theta = M_PI * i / rings, phi = 2 * M_PI * j / segments;
      points.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  points.emplace_back(0, 0, -1);
  PolygonMesh mesh;
  mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t v = 0; v < points.size(); ++v) mesh.vertices.row(v) = points[v].cwiseProduct(radii);
  const int last = static_cast<int>(points.size()) - 1, base = 1 + (rings - 2) * segments;
  for (int j = 0; j < segments; ++j) mesh.faces.add({0, 1 + j, 1 + (j + 1) % segments});
  for (int i = 0; i < rings - 2; ++i)
    for (int j = 0; j < segments; ++j) {
      const int a = 1 + i * segments + j, b = 1 + i * segments + (j + 1) % segments;
      mesh.faces.add({a, a + segments, b + segments, b});
    }
  for (int j = 0; j < segments; ++j) mesh.faces.add({base + j, last, base + (j + 1) % segments});
  return mesh;
}

// A torus around Z, quads, outward.
inline PolygonMesh torus(int segments, int rings, double major = 1.0, double minor = 0.4) {
  PolygonMesh mesh;
  mesh.vertices.resize(segments * rings, 3);
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < rings; ++j) {
      const double u = 2 * M_PI * i / segments, v = 2 * M_PI * j / rings;
      mesh.vertices.row(i * rings + j) << (major + minor * std::cos(v)) * std::cos(u),
          (major + minor * std::cos(v)) * std::sin(u), minor * std::sin(v);
    }
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < rings; ++j) {
      const int i1 = (i + 1) % segments, j1 = (j + 1) % rings;
      mesh.faces.add({i * rings + j, i1 * rings + j, i1 * rings + j1, i * rings + j1});
    }
  return mesh;
}

// The boundary of a union of unit voxels: an exact polycube, with the label of
// every face (its outward axis). Quads share grid vertices.
struct LabelledMesh {
  PolygonMesh mesh;
  std::vector<int> labels;
};

inline LabelledMesh voxel_surface(const std::set<std::array<int, 3>>& voxels) {
  LabelledMesh out;
  std::map<std::array<int, 3>, int> index;
  std::vector<Eigen::Vector3d> points;
  auto vertex = [&](std::array<int, 3> p) {
    auto [it, inserted] = index.emplace(p, static_cast<int>(points.size()));
    if (inserted) points.emplace_back(p[0], p[1], p[2]);
    return it->second;
  };
  for (const auto& c : voxels)
    for (int axis = 0; axis < 3; ++axis)
      for (int side = 0; side < 2; ++side) {
        std::array<int, 3> neighbour = c;
        neighbour[axis] += side == 0 ? 1 : -1;
        if (voxels.count(neighbour)) continue;
        const int u = (axis + 1) % 3, v = (axis + 2) % 3;
        std::array<int, 3> p = c;
        p[axis] += side == 0 ? 1 : 0;
        auto corner = [&](int du, int dv) {
          std::array<int, 3> q = p;
          q[u] += du;
          q[v] += dv;
          return vertex(q);
        };
        // (u, v, axis) is right-handed, so this order faces +axis; reverse for -axis.
        if (side == 0) out.mesh.faces.add({corner(0, 0), corner(1, 0), corner(1, 1), corner(0, 1)});
        else out.mesh.faces.add({corner(0, 0), corner(0, 1), corner(1, 1), corner(1, 0)});
        out.labels.push_back(2 * axis + side);
      }
  out.mesh.vertices.resize(static_cast<Eigen::Index>(points.size()), 3);
  for (size_t k = 0; k < points.size(); ++k) out.mesh.vertices.row(k) = points[k];
  return out;
}

// A block of voxels [0,nx) x [0,ny) x [0,nz) offset by `at`, for building shapes.
inline void add_block(std::set<std::array<int, 3>>& voxels, std::array<int, 3> at, int nx, int ny, int nz) {
  for (int x = 0; x < nx; ++x)
    for (int y = 0; y < ny; ++y)
      for (int z = 0; z < nz; ++z) voxels.insert({at[0] + x, at[1] + y, at[2] + z});
}

// The smooth shapes the plain method turns into polycubes with nearest-axis
// labels (docs/design.md section 2): a sphere, an axis-aligned ellipsoid, a torus.
inline std::vector<std::pair<std::string, PolygonMesh>> smooth_shapes(int torus_segments = 48, int torus_rings = 24) {
  return {{"sphere", uv_sphere(32, 16)},
          {"ellipsoid", uv_sphere(32, 16, Eigen::Vector3d(1.5, 1.0, 0.7))},
          {"torus " + std::to_string(torus_segments) + "x" + std::to_string(torus_rings),
           torus(torus_segments, torus_rings)}};
}

// A Möbius strip: `segments` quads around, `across` quads across, one half twist.
inline PolygonMesh moebius_strip(int segments, int across) {
  PolygonMesh mesh;
  const int columns = across + 1;
  mesh.vertices.resize(segments * columns, 3);
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < columns; ++j) {
      const double u = 2 * M_PI * i / segments, s = -0.4 + 0.8 * j / across;
      mesh.vertices.row(i * columns + j) << (1 + s * std::cos(u / 2)) * std::cos(u),
          (1 + s * std::cos(u / 2)) * std::sin(u), s * std::sin(u / 2);
    }
  for (int i = 0; i < segments; ++i)
    for (int j = 0; j < across; ++j) {
      const bool wrap = i + 1 == segments;
      // Going once around turns the strip over: column j meets column across - j.
      const int next = wrap ? 0 : i + 1;
      const int j0 = wrap ? across - j : j, j1 = wrap ? across - j - 1 : j + 1;
      mesh.faces.add({i * columns + j, next * columns + j0, next * columns + j1, i * columns + j + 1});
    }
  return mesh;
}

}  // namespace polycube::test_meshes
