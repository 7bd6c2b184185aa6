#include "use/uv_figures.h"

#include <cmath>

#include <Eigen/Dense>

#include "deform/quality.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"
#include "mesh/union_find.h"
#include "use/corner_of.h"

namespace polycube {
UvFigures uv_figures(const PolygonMesh& mesh, const CornerUvs& uvs) {
  if (uvs.rows() != static_cast<Eigen::Index>(mesh.faces.indices.size()))
    throw Error("there are " + std::to_string(uvs.rows()) + " UVs for " +
                std::to_string(mesh.faces.indices.size()) + " face corners");
  const PolygonFaces& faces = mesh.faces;
  const int face_count = faces.count();
  const MeshAdjacency adjacency = mesh_adjacency(faces, static_cast<int>(mesh.vertices.rows()));

  UvFigures out;
  // Islands and seams: two faces on one edge are joined when both ends keep their UVs.
  double uv_extent = (uvs.colwise().maxCoeff() - uvs.colwise().minCoeff()).norm();
  const double same = 1e-9 * std::max(uv_extent, 1e-300);
  UnionFind sets(face_count);
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    const int begin = adjacency.edge_offsets[e], end = adjacency.edge_offsets[e + 1];
    if (end - begin < 2) continue;
    bool seam = false;
    for (int i = begin + 1; i < end; ++i) {
      const int f = adjacency.edge_faces[begin], g = adjacency.edge_faces[i];
      bool joined = true;
      for (int v : adjacency.edges[e])
        joined = joined && (uvs.row(corner_of(faces, f, v)) - uvs.row(corner_of(faces, g, v))).norm() <= same;
      if (joined) sets.join(f, g);
      else seam = true;
    }
    if (seam)
      out.seam_length += (mesh.vertices.row(adjacency.edges[e][0]) - mesh.vertices.row(adjacency.edges[e][1])).norm();
  }
  std::vector<int> island(face_count, -1);
  for (int f = 0; f < face_count; ++f) {
    const int r = sets.root(f);
    if (island[r] < 0) island[r] = out.islands++;
    island[f] = island[r];
  }

  // Each triangle's map: its edges in a frame of its own plane, onto their UV edges.
  const Triangulation triangulation = triangulate(mesh.vertices, faces);
  const Eigen::Index count = triangulation.triangles.rows();
  std::vector<double> area(count), uv_area(count), ratio(count);
  double total_area = 0.0, total_uv = 0.0;
  for (Eigen::Index t = 0; t < count; ++t) {
    const int f = triangulation.face_of_triangle[t];
    Eigen::Vector3d p[3];
    Eigen::Vector2d q[3];
    for (int k = 0; k < 3; ++k) {
      const int v = triangulation.triangles(t, k);
      p[k] = mesh.vertices.row(v).transpose();
      q[k] = uvs.row(corner_of(faces, f, v)).transpose();
    }
    const Eigen::Vector3d e1 = p[1] - p[0], e2 = p[2] - p[0], n = e1.cross(e2);
    area[t] = 0.5 * n.norm();
    const Eigen::Vector2d d1 = q[1] - q[0], d2 = q[2] - q[0];
    uv_area[t] = 0.5 * (d1.x() * d2.y() - d1.y() * d2.x());
    total_area += area[t];
    total_uv += std::abs(uv_area[t]);
    if (!(area[t] > 0.0)) continue;
    const Eigen::Vector3d x = e1.normalized(), y = n.normalized().cross(x);
    Eigen::Matrix2d from, to;
    from << e1.dot(x), e2.dot(x), e1.dot(y), e2.dot(y);
    to << d1, d2;
    const Eigen::Vector2d sigma = Eigen::JacobiSVD<Eigen::Matrix2d>(to * from.inverse()).singularValues();
    ratio[t] = sigma[1] > 0.0 ? sigma[0] / sigma[1] : INFINITY;
  }
  // Flipped: against the sign of most of the UV area of its island.
  std::vector<double> signed_area(out.islands, 0.0);
  for (Eigen::Index t = 0; t < count; ++t) signed_area[island[triangulation.face_of_triangle[t]]] += uv_area[t];

  double weight = 0.0;
  for (Eigen::Index t = 0; t < count; ++t) {
    // Collapsed as the polycube's triangles are (docs/design.md section 4):
    // a UV area below 1e-3 of the triangle's share of the input's, scaled.
    // A polycube triangle collapsed to a sliver has a sliver of UV area, of
    // either sign, and a singular value ratio in the thousands: neither says
    // anything about the map.
    const bool no_uv_area =
        std::abs(uv_area[t]) <= kCollapsedAreaRatio * total_uv * area[t] / total_area || !std::isfinite(ratio[t]);
    if (no_uv_area) {
      out.collapsed_area += area[t];
      continue;
    }
    if (uv_area[t] * signed_area[island[triangulation.face_of_triangle[t]]] < 0.0) ++out.flipped;
    const double r = (std::abs(uv_area[t]) / total_uv) / (area[t] / total_area);
    out.angle_distortion += area[t] * ratio[t];
    out.area_distortion += area[t] * std::max(r, 1.0 / r);
    weight += area[t];
  }
  if (weight > 0.0) {
    out.angle_distortion /= weight;
    out.area_distortion /= weight;
  }
  if (total_area > 0.0) out.collapsed_area /= total_area;
  return out;
}

}  // namespace polycube
