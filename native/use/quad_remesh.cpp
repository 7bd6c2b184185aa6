#include "use/quad_remesh.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <map>
#include <unordered_map>

#include "labels/axis.h"
#include "mesh/components.h"
#include "mesh/mesh_adjacency.h"
#include "use/corner_of.h"
#include "use/polycube_surface.h"
#include "use/quantise_planes.h"
#include "use/relax_on_surface.h"
#include "use/straighten_boundaries.h"

namespace polycube {
namespace {

// (label or -1, component, x, y, z), positions in grid steps. Connected
// components of the input never share a vertex, even where their polycubes
// overlap (an eye inside its head): the component keeps them apart.
using Key = std::array<long, 5>;

struct KeyHash {
  size_t operator()(const Key& k) const {
    size_t h = 1469598103934665603ull;
    for (long v : k) h = (h ^ static_cast<size_t>(v)) * 1099511628211ull;
    return h;
  }
};

// One flat triangle of the polycube, in its plane.
struct FlatTriangle {
  int triangle, label, axis, component;
  long layer;                   // grid step of its plane
  Eigen::Vector2d corner[3];    // polycube coordinates along axes (axis+1)%3, (axis+2)%3
  double area2;                 // twice the signed area in that frame
};

// Barycentric coordinates of p in the triangle (its signed area twice: area2).
Eigen::Vector3d barycentric(const FlatTriangle& t, const Eigen::Vector2d& p) {
  auto cross = [](const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a.x() * b.y() - a.y() * b.x(); };
  const double w0 = cross(t.corner[1] - p, t.corner[2] - p) / t.area2;
  const double w1 = cross(t.corner[2] - p, t.corner[0] - p) / t.area2;
  return {w0, w1, 1.0 - w0 - w1};
}

struct Placement {
  int flat = -1;                 // index into the flat triangles
  Eigen::Vector3d weights;
  double score = -INFINITY;      // the smallest weight: larger is further inside
};

std::string number(double x) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", x);
  return text;
}

}  // namespace

QuadRemesh quad_remesh(const PolygonMesh& input, const Vertices& polycube, const std::vector<int>& labels,
                       const QuadRemeshOptions& options) {
  const PolycubeSurface surface = polycube_surface(input, polycube, labels);
  if (!(options.edge_length > 0.0) || !std::isfinite(options.edge_length))
    throw Error("the edge length must be a positive number");
  QuadRemesh out;
  const double h = options.edge_length * surface.area_scale;
  out.grid_spacing = h;
  const Eigen::RowVector3d extent = polycube.colwise().maxCoeff() - polycube.colwise().minCoeff();
  if (h > extent.maxCoeff())
    throw Error("the edge length " + number(options.edge_length) + " is larger than the model (" +
                number(extent.maxCoeff() / surface.area_scale) + " across at most)");

  // The flat triangles and the planes of each axis.
  const Triangles& triangles = surface.triangulation.triangles;
  const double flat_tolerance = 1e-7 * surface.diagonal;
  const Components component = components(static_cast<int>(polycube.rows()), triangles);
  std::vector<FlatTriangle> flats;
  std::array<std::vector<double>, 3> plane_coordinates;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int f = surface.triangulation.face_of_triangle[t];
    if (!surface.face_carries_area[f]) continue;
    const int label = surface.face_label[f], a = label / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    FlatTriangle flat{static_cast<int>(t), label, a, component.of_vertex[triangles(t, 0)], 0, {}, 0.0};
    double low = INFINITY, high = -INFINITY;
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, k);
      flat.corner[k] = {polycube(v, b), polycube(v, c)};
      low = std::min(low, polycube(v, a));
      high = std::max(high, polycube(v, a));
    }
    if (high - low > flat_tolerance)
      throw Error("the polycube is not exact: face " + std::to_string(f) +
                  " is not flat on its axis (let the solver run until it converges)");
    const Eigen::Vector2d e1 = flat.corner[1] - flat.corner[0], e2 = flat.corner[2] - flat.corner[0];
    flat.area2 = (e1.x() * e2.y() - e1.y() * e2.x()) * (label % 2 == 0 ? 1.0 : -1.0);
    // A triangle of a flat polygon may still be a sliver with no area of its own:
    // collapsed (docs/design.md section 4) when turned over, else no grid point can tell.
    if (!(std::abs(flat.area2) > 1e-14 * surface.diagonal * surface.diagonal)) continue;
    const Eigen::Vector3d i0 = input.vertices.row(triangles(t, 0)), i1 = input.vertices.row(triangles(t, 1)),
                          i2 = input.vertices.row(triangles(t, 2));
    const double collapsed = 1e-3 * surface.area_scale * surface.area_scale * (i1 - i0).cross(i2 - i0).norm();
    if (flat.area2 < 0.0 && -flat.area2 <= collapsed) continue;
    if (flat.area2 < 0.0)
      throw Error("the polycube has a flipped triangle in face " + std::to_string(f) +
                  ": a folded polycube cannot be mapped back onto the mesh");
    flat.area2 *= label % 2 == 0 ? 1.0 : -1.0;  // back to the frame's own sign for barycentric()
    flat.layer = 0;
    plane_coordinates[a].push_back(low);
    flats.push_back(flat);
  }
  std::array<AxisGrid, 3> grid;
  for (int a = 0; a < 3; ++a) grid[a] = quantise_planes(plane_coordinates[a], h, flat_tolerance);

  // Open boundaries laid along grid lines (straighten_boundaries): straight rows of quads
  // follow them instead of a staircase. The planes stay, so only the flat corners change.
  const MeshAdjacency input_adjacency = mesh_adjacency(input.faces, static_cast<int>(input.vertices.rows()));
  bool input_open = false;
  for (int e = 0; e < input_adjacency.edge_count(); ++e) input_open |= input_adjacency.faces_of_edge(e) == 1;
  if (input_open) {
    const StraightBoundaries straight = straighten_boundaries(input, polycube, surface, grid, 6.0 * h);
    out.boundary_loops = straight.loops;
    out.straightened_loops = straight.straightened;
    for (FlatTriangle& t : flats) {
      const int b = (t.axis + 1) % 3, c = (t.axis + 2) % 3;
      for (int k = 0; k < 3; ++k) {
        const int v = triangles(t.triangle, k);
        t.corner[k] = {straight.polycube(v, b), straight.polycube(v, c)};
      }
      const Eigen::Vector2d e1 = t.corner[1] - t.corner[0], e2 = t.corner[2] - t.corner[0];
      t.area2 = e1.x() * e2.y() - e1.y() * e2.x();
    }
    // A triangle laid flat on a straightened run has no area left: like a sliver, it holds no grid point.
    flats.erase(std::remove_if(flats.begin(), flats.end(),
                               [&](const FlatTriangle& t) {
                                 return !(std::abs(t.area2) > 1e-14 * surface.diagonal * surface.diagonal);
                               }),
                flats.end());
  }

  // Grid squares by the flat triangle under their centre, grid vertices by the
  // flat triangle that holds them deepest inside.
  std::unordered_map<Key, int, KeyHash> square_of;
  std::vector<Key> squares;
  std::vector<int> square_flat;
  std::vector<double> square_depth;  // the smallest barycentric weight of its centre: larger is further inside
  std::unordered_map<Key, Placement, KeyHash> placement;
  const double inside = -1e-9;
  for (size_t i = 0; i < flats.size(); ++i) {
    FlatTriangle& t = flats[i];
    const int a = t.axis, b = (a + 1) % 3, c = (a + 2) % 3;
    const int v0 = triangles(t.triangle, 0);
    t.layer = std::lround(grid[a].to_grid(polycube(v0, a)));
    double lo[2] = {INFINITY, INFINITY}, hi[2] = {-INFINITY, -INFINITY};
    for (int k = 0; k < 3; ++k) {
      const double gb = grid[b].to_grid(t.corner[k].x()), gc = grid[c].to_grid(t.corner[k].y());
      lo[0] = std::min(lo[0], gb), hi[0] = std::max(hi[0], gb);
      lo[1] = std::min(lo[1], gc), hi[1] = std::max(hi[1], gc);
    }
    auto key = [&](int label, long gi, long gj) {
      Key k{label, t.component, 0, 0, 0};
      k[2 + a] = t.layer;
      k[2 + b] = gi;
      k[2 + c] = gj;
      return k;
    };
    // Square centres at half steps.
    for (long gi = std::lround(std::ceil(lo[0] - 0.5)); gi + 0.5 <= hi[0]; ++gi)
      for (long gj = std::lround(std::ceil(lo[1] - 0.5)); gj + 0.5 <= hi[1]; ++gj) {
        const Eigen::Vector2d p(grid[b].from_grid(gi + 0.5), grid[c].from_grid(gj + 0.5));
        const double depth = barycentric(t, p).minCoeff();
        if (depth < inside) continue;
        const Key k = key(t.label, gi, gj);
        if (square_of.emplace(k, static_cast<int>(squares.size())).second) {
          squares.push_back(k);
          square_flat.push_back(static_cast<int>(i));
          square_depth.push_back(depth);
        }
      }
    // Grid vertices.
    for (long gi = std::lround(std::ceil(lo[0])); gi <= hi[0]; ++gi)
      for (long gj = std::lround(std::ceil(lo[1])); gj <= hi[1]; ++gj) {
        const Eigen::Vector2d p(grid[b].from_grid(static_cast<double>(gi)), grid[c].from_grid(static_cast<double>(gj)));
        const Eigen::Vector3d w = barycentric(t, p);
        if (w.minCoeff() < inside) continue;
        Placement& best = placement[key(-1, gi, gj)];
        if (w.minCoeff() > best.score) best = {static_cast<int>(i), w, w.minCoeff()};
      }
  }
  if (squares.empty()) throw Error("no grid square fits on the polycube: choose a smaller edge length");

  // Quads: the square's corners counter-clockwise seen from its label's side.
  std::vector<std::array<Key, 4>> square_corners(squares.size());
  for (size_t s = 0; s < squares.size(); ++s) {
    const Key& k = squares[s];
    const int label = static_cast<int>(k[0]), a = label / 2, b = (a + 1) % 3, c = (a + 2) % 3;
    static constexpr int kCorner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int q = 0; q < 4; ++q) {
      Key corner{-1, k[1], k[2], k[3], k[4]};
      corner[2 + b] += kCorner[q][0];
      corner[2 + c] += kCorner[q][1];
      square_corners[s][q] = corner;
    }
    if (label % 2 == 1) std::swap(square_corners[s][1], square_corners[s][3]);
  }

  // Manifold: every edge in at most two quads, walked once each way. Where the
  // input is open, a boundary running slantwise across the grid can leave two
  // squares on one side of a grid edge (each centre on the surface, their edge
  // not): the one whose centre lies deeper inside its triangle stays. Elsewhere
  // two such squares mean the polycube touches itself.
  std::vector<char> dropped(squares.size(), 0);
  for (;;) {
    std::map<std::array<Key, 2>, std::vector<int>> users;  // directed edge -> squares walking it
    for (size_t s = 0; s < squares.size(); ++s)
      if (!dropped[s])
        for (int q = 0; q < 4; ++q) users[{square_corners[s][q], square_corners[s][(q + 1) % 4]}].push_back(int(s));
    bool changed = false;
    for (const auto& [edge, walkers] : users) {
      if (walkers.size() < 2) continue;
      if (!input_open) {
        const Key& k = edge[0];
        throw Error("the polycube touches itself near grid point (" + std::to_string(k[2]) + ", " +
                    std::to_string(k[3]) + ", " + std::to_string(k[4]) +
                    "): its quad mesh would not be manifold");
      }
      const int keep = *std::max_element(walkers.begin(), walkers.end(),
                                         [&](int x, int y) { return square_depth[x] < square_depth[y]; });
      for (int s : walkers)
        if (s != keep) dropped[s] = changed = true;
    }
    if (!changed) break;
  }

  std::unordered_map<Key, int, KeyHash> vertex_of;
  std::vector<Key> vertex_keys;
  std::vector<int> vertex_square;  // a square using the vertex, for the fallback below
  out.mesh.faces.indices.reserve(4 * squares.size());
  for (size_t s = 0; s < squares.size(); ++s) {
    if (dropped[s]) continue;
    std::array<int, 4> quad;
    for (int q = 0; q < 4; ++q) {
      auto [it, added] = vertex_of.emplace(square_corners[s][q], static_cast<int>(vertex_keys.size()));
      if (added) {
        vertex_keys.push_back(square_corners[s][q]);
        vertex_square.push_back(static_cast<int>(s));
      }
      quad[q] = it->second;
    }
    out.mesh.faces.add({quad[0], quad[1], quad[2], quad[3]});
    out.source_face.push_back(surface.triangulation.face_of_triangle[flats[square_flat[s]].triangle]);
    out.label.push_back(static_cast<int>(squares[s][0]));
  }

  // Every grid vertex back onto the input: the same barycentric coordinates on the input triangle.
  const int vertex_count = static_cast<int>(vertex_keys.size());
  std::vector<SurfacePoint> points(vertex_count);
  for (int v = 0; v < vertex_count; ++v) {
    auto found = placement.find(vertex_keys[v]);
    Placement p;
    if (found != placement.end()) {
      p = found->second;
    } else {
      // Off the surface's flat part (an open boundary): the nearest point of the square's own triangle.
      p.flat = square_flat[vertex_square[v]];
      const FlatTriangle& t = flats[p.flat];
      const int b = (t.axis + 1) % 3, c = (t.axis + 2) % 3;
      p.weights = barycentric(t, {grid[b].from_grid(static_cast<double>(vertex_keys[v][2 + b])),
                                  grid[c].from_grid(static_cast<double>(vertex_keys[v][2 + c]))});
    }
    points[v] = {flats[p.flat].triangle, p.weights.cwiseMax(0.0) / p.weights.cwiseMax(0.0).sum()};
  }

  // Edges, valences, open edges, and the polycube's edges (two quads of different labels).
  std::map<std::array<int, 2>, std::array<int, 2>> edge_quads;  // (low, high) -> its quads (-1: none)
  for (int f = 0; f < out.mesh.faces.count(); ++f)
    for (int q = 0; q < 4; ++q) {
      const int u = out.mesh.faces.indices[4 * f + q], w = out.mesh.faces.indices[4 * f + (q + 1) % 4];
      auto [it, added] = edge_quads.try_emplace({std::min(u, w), std::max(u, w)}, std::array<int, 2>{f, -1});
      if (!added) it->second[1] = f;
    }
  std::vector<int> valence(vertex_count, 0), open(vertex_count, 0);
  std::vector<std::vector<int>> all_neighbours(vertex_count), crease_neighbours(vertex_count);
  for (const auto& [edge, quads] : edge_quads) {
    for (int v : edge) ++valence[v];
    all_neighbours[edge[0]].push_back(edge[1]);
    all_neighbours[edge[1]].push_back(edge[0]);
    if (quads[1] < 0) {
      ++out.open_edges;
      for (int v : edge) open[v] = 1;
    } else if (out.label[quads[0]] != out.label[quads[1]]) {
      crease_neighbours[edge[0]].push_back(edge[1]);
      crease_neighbours[edge[1]].push_back(edge[0]);
    }
  }
  for (int v = 0; v < vertex_count; ++v)
    if (valence[v] != (open[v] ? 3 : 4)) ++out.irregular_vertices;

  // Even the spacing on the input (relax_on_surface): a vertex inside a face of
  // the polycube moves among its four neighbours, one on a polycube edge along
  // that edge (the input's feature it follows stays sharp); polycube corners,
  // irregular vertices and the input's boundary stay.
  std::vector<std::vector<int>> neighbours(vertex_count);
  for (int v = 0; v < vertex_count; ++v) {
    if (open[v] || valence[v] != 4) continue;
    if (crease_neighbours[v].empty())
      neighbours[v] = all_neighbours[v];
    else if (crease_neighbours[v].size() == 2)
      neighbours[v] = crease_neighbours[v];
  }
  // Only where the carried grid is stretched (an edge over 1.6 h, and two rings
  // around it): quads bridging a collapsed strip, a sliver's few points far
  // apart. Elsewhere the grid follows the input's own triangles, its features too.
  const Vertices carried = relax_on_surface(input.vertices, triangles, neighbours, 0, points);
  std::vector<char> moves(vertex_count, 0);
  for (const auto& [edge, quads] : edge_quads)
    if ((carried.row(edge[0]) - carried.row(edge[1])).norm() > 1.6 * options.edge_length)
      moves[edge[0]] = moves[edge[1]] = 1;
  for (int ring = 0; ring < 2; ++ring) {
    std::vector<char> grown = moves;
    for (const auto& [edge, quads] : edge_quads)
      if (moves[edge[0]] || moves[edge[1]]) grown[edge[0]] = grown[edge[1]] = 1;
    moves.swap(grown);
  }
  for (int v = 0; v < vertex_count; ++v)
    if (!moves[v]) neighbours[v].clear();
  out.mesh.vertices = relax_on_surface(input.vertices, triangles, neighbours, options.relax_iterations, points,
                                       out.mesh.faces);

  out.vertex_corners.resize(vertex_count, 3);
  out.vertex_weights.resize(vertex_count, 3);
  for (int v = 0; v < vertex_count; ++v) {
    const int t = points[v].triangle;
    const int face = surface.triangulation.face_of_triangle[t];
    for (int k = 0; k < 3; ++k) out.vertex_corners(v, k) = corner_of(input.faces, face, triangles(t, k));
    out.vertex_weights.row(v) = points[v].weights.transpose();
  }
  return out;
}

}  // namespace polycube
