#include "use/polycube_surface.h"

#include <algorithm>
#include <cmath>
#include <deque>

#include <Eigen/Geometry>

#include "labels/axis.h"
#include "mesh/check_input.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {
namespace {

double polygon_area(const Vertices& v, const PolygonFaces& faces, int f) {
  return 0.5 * newell_normal(v, faces, f).norm();
}

}  // namespace

PolycubeSurface polycube_surface(const PolygonMesh& input, const Vertices& polycube,
                                 const std::vector<int>& labels) {
  check_input(input, labels.empty() ? nullptr : &labels);
  if (polycube.rows() != input.vertices.rows())
    throw Error("the polycube has " + std::to_string(polycube.rows()) + " vertices but the mesh has " +
                std::to_string(input.vertices.rows()) + ": it is not this mesh's polycube");
  if (!polycube.allFinite()) throw Error("the polycube has a non-finite coordinate");
  const int face_count = input.faces.count();
  PolycubeSurface out;
  out.triangulation = triangulate(input.vertices, input.faces);

  std::vector<double> area_in(face_count), area_out(face_count);
  double total_in = 0.0, total_out = 0.0;
  for (int f = 0; f < face_count; ++f) {
    area_in[f] = polygon_area(input.vertices, input.faces, f);
    area_out[f] = polygon_area(polycube, input.faces, f);
    total_in += area_in[f];
    total_out += area_out[f];
  }
  if (!(total_in > 0.0) || !(total_out > 0.0)) throw Error("the mesh or its polycube has no area");
  out.area_scale = std::sqrt(total_out / total_in);
  out.diagonal = (polycube.colwise().maxCoeff() - polycube.colwise().minCoeff()).norm();

  // Collapsed as in docs/design.md section 4: below 1e-3 s^2 of its own input area.
  const double s2 = out.area_scale * out.area_scale;
  out.face_carries_area.resize(face_count);
  out.face_label.assign(face_count, kUnlabelled);
  std::vector<Eigen::Vector3d> normal(face_count);
  int flipped = 0, first_flipped = -1;
  for (int f = 0; f < face_count; ++f) {
    out.face_carries_area[f] = area_out[f] > 1e-3 * s2 * area_in[f] && area_out[f] > 0.0;
    if (!out.face_carries_area[f]) {
      if (!labels.empty()) out.face_label[f] = labels[f];
      continue;
    }
    normal[f] = newell_normal(polycube, input.faces, f).normalized();
    out.face_label[f] = nearest_axis(normal[f]);
    if (!labels.empty() && labels[f] != kUnlabelled && normal[f].dot(label_axis(labels[f])) < 0.0) {
      if (flipped++ == 0) first_flipped = f;
    }
  }
  if (flipped)
    throw Error("the polycube has " + std::to_string(flipped) + " flipped face" + (flipped > 1 ? "s" : "") +
                " (face " + std::to_string(first_flipped) +
                " first) facing away from its label: a folded polycube cannot be mapped back onto the mesh");

  // A polygon that is not convex on the polycube may have a triangle of the
  // input's split turned over there, though the polygon itself is not: split
  // such polygons as the polycube sees them, so every triangle keeps its side.
  const Triangulation on_polycube = triangulate(polycube, input.faces);
  std::vector<char> resplit(face_count, 0);
  const Triangles& t = out.triangulation.triangles;
  for (Eigen::Index k = 0; k < t.rows(); ++k) {
    const int f = out.triangulation.face_of_triangle[k];
    if (!out.face_carries_area[f]) continue;
    const Eigen::Vector3d a = polycube.row(t(k, 0)), b = polycube.row(t(k, 1)), c = polycube.row(t(k, 2));
    if ((b - a).cross(c - a).dot(normal[f]) < 0.0) resplit[f] = 1;
  }
  if (std::find(resplit.begin(), resplit.end(), 1) != resplit.end()) {
    Triangulation mixed;
    std::vector<Eigen::RowVector3i> rows;
    for (const Triangulation* from : {static_cast<const Triangulation*>(&out.triangulation), &on_polycube})
      for (Eigen::Index k = 0; k < from->triangles.rows(); ++k) {
        const int f = from->face_of_triangle[k];
        if (resplit[f] == (from == &on_polycube)) {
          rows.push_back(from->triangles.row(k));
          mixed.face_of_triangle.push_back(f);
        }
      }
    mixed.triangles.resize(static_cast<Eigen::Index>(rows.size()), 3);
    for (size_t k = 0; k < rows.size(); ++k) mixed.triangles.row(k) = rows[k];
    out.triangulation = std::move(mixed);
  }

  const MeshAdjacency adjacency = mesh_adjacency(input.faces, static_cast<int>(input.vertices.rows()));
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    if (adjacency.faces_of_edge(e) != 2) continue;
    const int a = adjacency.edge_faces[adjacency.edge_offsets[e]], b = adjacency.edge_faces[adjacency.edge_offsets[e] + 1];
    // A fold the input has already (a sharp crease) is the mesh's, not the polycube's.
    if (out.face_carries_area[a] && out.face_carries_area[b] && normal[a].dot(normal[b]) < -0.5 &&
        newell_normal(input.vertices, input.faces, a).dot(newell_normal(input.vertices, input.faces, b)) >= 0.0)
      throw Error("the polycube is folded between faces " + std::to_string(a) + " and " + std::to_string(b) +
                  " (their normals are more than 120 degrees apart): it cannot be mapped back onto the mesh");
  }

  // Faces without area and without a given label take a neighbour's, breadth first.
  const std::vector<std::vector<int>> neighbours = face_neighbours(adjacency, face_count);
  std::deque<int> queue;
  for (int f = 0; f < face_count; ++f)
    if (out.face_label[f] != kUnlabelled) queue.push_back(f);
  while (!queue.empty()) {
    const int f = queue.front();
    queue.pop_front();
    for (int g : neighbours[f])
      if (out.face_label[g] == kUnlabelled) {
        out.face_label[g] = out.face_label[f];
        queue.push_back(g);
      }
  }
  for (int& label : out.face_label)
    if (label == kUnlabelled) label = 0;  // a component with no area at all
  return out;
}

}  // namespace polycube
