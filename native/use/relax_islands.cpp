#include "use/relax_islands.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCholesky>
#include <map>

#include "mesh/triangulate.h"
#include "use/corner_of.h"

namespace polycube {

void relax_islands(const PolygonMesh& input, const std::vector<int>& island_of_face, int islands, CornerUvs& uvs,
                   double area_scale) {
  const PolygonFaces& faces = input.faces;
  // One unknown point per (island, vertex): seams separate islands only.
  std::map<std::pair<int, int>, int> point_of;
  std::vector<int> point_of_corner(faces.indices.size()), island_of_point;
  std::vector<Eigen::Vector2d> start;
  for (int f = 0; f < faces.count(); ++f)
    for (int k = faces.offsets[f]; k < faces.offsets[f + 1]; ++k) {
      auto [it, added] = point_of.emplace(std::pair{island_of_face[f], faces.indices[k]}, static_cast<int>(start.size()));
      if (added) {
        start.push_back(uvs.row(k).transpose());
        island_of_point.push_back(island_of_face[f]);
      }
      point_of_corner[k] = it->second;
    }
  const int n = static_cast<int>(start.size());

  // Pins: per island, the points with the smallest and the largest u + v.
  std::vector<int> low(islands, -1), high(islands, -1);
  for (int p = 0; p < n; ++p) {
    const int i = island_of_point[p];
    if (low[i] < 0 || start[p].sum() < start[low[i]].sum()) low[i] = p;
    if (high[i] < 0 || start[p].sum() > start[high[i]].sum()) high[i] = p;
  }
  // An island the polycube shrank to a point or a segment across u + v: any second
  // point, set apart by the input's own extent so the island can unfold.
  const double extent = area_scale * (input.vertices.colwise().maxCoeff() - input.vertices.colwise().minCoeff()).norm();
  for (int p = 0; p < n; ++p) {
    const int i = island_of_point[p];
    if (high[i] == low[i] && p != low[i]) high[i] = p;
  }
  std::vector<char> pinned(n, 0);
  for (int i = 0; i < islands; ++i) {
    if (low[i] < 0 || high[i] == low[i]) continue;
    if ((start[high[i]] - start[low[i]]).norm() <= 1e-12 * extent)
      start[high[i]] = start[low[i]] + Eigen::Vector2d(1e-3 * extent, 0.0);
    pinned[low[i]] = pinned[high[i]] = 1;
  }
  // Unknowns: u then v of each free point.
  std::vector<int> unknown(n, -1);
  int free_count = 0;
  for (int p = 0; p < n; ++p)
    if (!pinned[p]) unknown[p] = free_count++;

  // Per triangle, sqrt(area) times the two Cauchy-Riemann residuals
  // u_x - v_y and u_y + v_x in a frame of its own plane.
  const Triangulation triangulation = triangulate(input.vertices, faces);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> rhs;
  std::vector<double> island_area(islands, 0.0);
  int row = 0;
  for (Eigen::Index t = 0; t < triangulation.triangles.rows(); ++t) {
    const int f = triangulation.face_of_triangle[t];
    int point[3];
    Eigen::Vector3d x[3];
    for (int k = 0; k < 3; ++k) {
      const int v = triangulation.triangles(t, k);
      point[k] = point_of_corner[corner_of(faces, f, v)];
      x[k] = input.vertices.row(v).transpose();
    }
    const Eigen::Vector3d e1 = x[1] - x[0], e2 = x[2] - x[0], normal = e1.cross(e2);
    const double area = 0.5 * normal.norm();
    if (!(area > 0.0)) continue;
    island_area[island_of_face[f]] += area;
    const Eigen::Vector3d ax = e1.normalized(), ay = normal.normalized().cross(ax);
    const Eigen::Vector2d q[3] = {{0.0, 0.0}, {e1.dot(ax), e1.dot(ay)}, {e2.dot(ax), e2.dot(ay)}};
    // Gradient of the linear interpolant: d/dx and d/dy weights of the three corners.
    double gx[3], gy[3];
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector2d& a = q[(k + 1) % 3];
      const Eigen::Vector2d& b = q[(k + 2) % 3];
      gx[k] = (a.y() - b.y()) / (2.0 * area);
      gy[k] = (b.x() - a.x()) / (2.0 * area);
    }
    const double w = std::sqrt(area);
    // Row r1: u_x - v_y; row r2: u_y + v_x.
    double b1 = 0.0, b2 = 0.0;
    for (int k = 0; k < 3; ++k) {
      const int p = point[k];
      const double c1u = w * gx[k], c1v = -w * gy[k], c2u = w * gy[k], c2v = w * gx[k];
      if (pinned[p]) {
        b1 -= c1u * start[p].x() + c1v * start[p].y();
        b2 -= c2u * start[p].x() + c2v * start[p].y();
        continue;
      }
      entries.emplace_back(row, 2 * unknown[p], c1u);
      entries.emplace_back(row, 2 * unknown[p] + 1, c1v);
      entries.emplace_back(row + 1, 2 * unknown[p], c2u);
      entries.emplace_back(row + 1, 2 * unknown[p] + 1, c2v);
    }
    rhs.push_back(b1);
    rhs.push_back(b2);
    row += 2;
  }
  if (free_count == 0) return;
  Eigen::SparseMatrix<double> a(row, 2 * free_count);
  a.setFromTriplets(entries.begin(), entries.end());
  const Eigen::Map<const Eigen::VectorXd> b(rhs.data(), row);
  const Eigen::SparseMatrix<double> normal_matrix = (a.transpose() * a).pruned();
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(normal_matrix);
  if (solver.info() != Eigen::Success) throw Error("the conformal relaxation of the UV islands failed");
  const Eigen::VectorXd solution = solver.solve(a.transpose() * b);
  if (solver.info() != Eigen::Success || !solution.allFinite())
    throw Error("the conformal relaxation of the UV islands failed");

  std::vector<Eigen::Vector2d> relaxed = start;
  for (int p = 0; p < n; ++p)
    if (!pinned[p]) relaxed[p] = {solution[2 * unknown[p]], solution[2 * unknown[p] + 1]};
  // One texel density: each island's UV area to area_scale^2 times its input area.
  std::vector<double> uv_area(islands, 0.0);
  for (Eigen::Index t = 0; t < triangulation.triangles.rows(); ++t) {
    const int f = triangulation.face_of_triangle[t];
    Eigen::Vector2d q[3];
    for (int k = 0; k < 3; ++k) q[k] = relaxed[point_of_corner[corner_of(faces, f, triangulation.triangles(t, k))]];
    const Eigen::Vector2d d1 = q[1] - q[0], d2 = q[2] - q[0];
    uv_area[island_of_face[f]] += 0.5 * (d1.x() * d2.y() - d1.y() * d2.x());
  }
  for (int p = 0; p < n; ++p) {
    const int i = island_of_point[p];
    const double scale = uv_area[i] > 0.0 ? area_scale * std::sqrt(island_area[i] / uv_area[i]) : 1.0;
    relaxed[p] = start[low[i]] + scale * (relaxed[p] - start[low[i]]);
  }
  for (size_t k = 0; k < point_of_corner.size(); ++k) uvs.row(k) = relaxed[point_of_corner[k]].transpose();
}

}  // namespace polycube
