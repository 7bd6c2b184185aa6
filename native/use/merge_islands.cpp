#include "use/merge_islands.h"

#include <algorithm>
#include <map>
#include <set>

#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"
#include "mesh/union_find.h"
#include "use/relax_islands.h"
#include "use/uv_figures.h"

namespace polycube {
namespace {

// The faces as a mesh of their own (same vertices), with their corners' UVs.
PolygonMesh sub_mesh(const PolygonMesh& input, const std::vector<int>& faces, const CornerUvs& uvs, CornerUvs& sub_uvs) {
  PolygonMesh sub;
  sub.vertices = input.vertices;
  std::vector<int> corners;
  for (int f : faces) {
    for (int k = input.faces.offsets[f]; k < input.faces.offsets[f + 1]; ++k) {
      sub.faces.indices.push_back(input.faces.indices[k]);
      corners.push_back(k);
    }
    sub.faces.offsets.push_back(static_cast<int>(sub.faces.indices.size()));
  }
  sub_uvs.resize(static_cast<Eigen::Index>(corners.size()), 2);
  for (size_t c = 0; c < corners.size(); ++c) sub_uvs.row(c) = uvs.row(corners[c]);
  return sub;
}

bool segments_cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  auto side = [](const Eigen::Vector2d& p, const Eigen::Vector2d& q, const Eigen::Vector2d& r) {
    const double s = (q.x() - p.x()) * (r.y() - p.y()) - (q.y() - p.y()) * (r.x() - p.x());
    return (s > 0.0) - (s < 0.0);
  };
  return side(a, b, c) * side(a, b, d) < 0 && side(c, d, a) * side(c, d, b) < 0;
}

// A disk (one piece, Euler characteristic 1) whose UV boundary does not cross itself.
bool unfolds_as_disk(const PolygonMesh& sub, const CornerUvs& sub_uvs) {
  const MeshAdjacency adjacency = mesh_adjacency(sub.faces, static_cast<int>(sub.vertices.rows()));
  std::set<int> used(sub.faces.indices.begin(), sub.faces.indices.end());
  const long euler = static_cast<long>(used.size()) - adjacency.edge_count() + sub.faces.count();
  if (euler != 1) return false;
  std::vector<std::array<Eigen::Vector2d, 2>> boundary;
  std::vector<std::array<int, 2>> ends;
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    if (adjacency.faces_of_edge(e) != 1) continue;
    const int f = adjacency.edge_faces[adjacency.edge_offsets[e]];
    std::array<Eigen::Vector2d, 2> segment;
    for (int i = 0; i < 2; ++i)
      for (int k = sub.faces.offsets[f]; k < sub.faces.offsets[f + 1]; ++k)
        if (sub.faces.indices[k] == adjacency.edges[e][i]) segment[i] = sub_uvs.row(k).transpose();
    boundary.push_back(segment);
    ends.push_back(adjacency.edges[e]);
  }
  for (size_t i = 0; i < boundary.size(); ++i)
    for (size_t j = i + 1; j < boundary.size(); ++j) {
      const bool touching = ends[i][0] == ends[j][0] || ends[i][0] == ends[j][1] || ends[i][1] == ends[j][0] ||
                            ends[i][1] == ends[j][1];
      if (!touching && segments_cross(boundary[i][0], boundary[i][1], boundary[j][0], boundary[j][1])) return false;
    }
  return true;
}

}  // namespace

void merge_islands(const PolygonMesh& input, std::vector<int>& island_of_face, int& islands, CornerUvs& uvs,
                   double area_scale, double slack) {
  const int face_count = input.faces.count();
  std::vector<std::vector<int>> faces_of(islands);
  for (int f = 0; f < face_count; ++f) faces_of[island_of_face[f]].push_back(f);
  // Each island's angle distortion and area, as its own mesh.
  std::vector<double> distortion(islands), stretch(islands), area(islands);
  auto measure = [&](const std::vector<int>& faces, const CornerUvs& from, double& d, double& s, double& a) {
    CornerUvs sub_uvs;
    const PolygonMesh sub = sub_mesh(input, faces, from, sub_uvs);
    const UvFigures figures = uv_figures(sub, sub_uvs);
    d = figures.angle_distortion;
    s = figures.area_distortion;
    a = 0.0;
    for (int f = 0; f < sub.faces.count(); ++f) a += 0.5 * newell_normal(sub.vertices, sub.faces, f).norm();
  };
  for (int i = 0; i < islands; ++i) measure(faces_of[i], uvs, distortion[i], stretch[i], area[i]);

  // Shared seam length of each pair of neighbouring islands.
  const MeshAdjacency adjacency = mesh_adjacency(input.faces, static_cast<int>(input.vertices.rows()));
  std::map<std::pair<int, int>, double> seam;
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    if (adjacency.faces_of_edge(e) != 2) continue;
    const int a = island_of_face[adjacency.edge_faces[adjacency.edge_offsets[e]]];
    const int b = island_of_face[adjacency.edge_faces[adjacency.edge_offsets[e] + 1]];
    if (a != b)
      seam[{std::min(a, b), std::max(a, b)}] +=
          (input.vertices.row(adjacency.edges[e][0]) - input.vertices.row(adjacency.edges[e][1])).norm();
  }
  std::vector<std::pair<double, std::pair<int, int>>> pairs;
  for (const auto& [pair, length] : seam) pairs.push_back({-length, pair});
  std::sort(pairs.begin(), pairs.end());

  UnionFind merged(islands);
  for (const auto& [negative_length, pair] : pairs) {
    const int a = merged.root(pair.first), b = merged.root(pair.second);
    if (a == b) continue;
    std::vector<int> faces = faces_of[a];
    faces.insert(faces.end(), faces_of[b].begin(), faces_of[b].end());
    CornerUvs sub_uvs;
    const PolygonMesh sub = sub_mesh(input, faces, uvs, sub_uvs);
    relax_islands(sub, std::vector<int>(faces.size(), 0), 1, sub_uvs, area_scale);
    const UvFigures figures = uv_figures(sub, sub_uvs);
    const double before = (distortion[a] * area[a] + distortion[b] * area[b]) / (area[a] + area[b]);
    const double stretch_before = (stretch[a] * area[a] + stretch[b] * area[b]) / (area[a] + area[b]);
    if (figures.flipped > 0 || figures.islands != 1 || figures.angle_distortion > before + slack ||
        figures.area_distortion > stretch_before + slack ||
        !unfolds_as_disk(sub, sub_uvs))
      continue;
    merged.join(a, b);
    const int root = merged.root(a);
    const int other = root == a ? b : a;
    int c = 0;
    for (int f : faces)
      for (int k = input.faces.offsets[f]; k < input.faces.offsets[f + 1]; ++k) uvs.row(k) = sub_uvs.row(c++);
    faces_of[root] = std::move(faces);
    faces_of[other].clear();
    distortion[root] = figures.angle_distortion;
    stretch[root] = figures.area_distortion;
    area[root] += area[other];
  }
  std::vector<int> number(islands, -1);
  int count = 0;
  for (int f = 0; f < face_count; ++f) {
    const int r = merged.root(island_of_face[f]);
    if (number[r] < 0) number[r] = count++;
    island_of_face[f] = number[r];
  }
  islands = count;
}

}  // namespace polycube
