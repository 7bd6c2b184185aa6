#include "use/straighten_boundaries.h"

#include <Eigen/Geometry>
#include <Eigen/SparseCore>
#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <utility>

#include "linear_algebra/sparse_cholesky.h"
#include "use/untangle_in_charts.h"

namespace polycube {
namespace {

// A run of a boundary loop: edges first .. first + count - 1 (cyclic), at a constant coordinate of `axis`.
struct Run {
  int first, count, axis;
};

// Twice the signed area of triangle t on the polycube p, seen from its face's label.
double flat_area2(const Vertices& p, const Triangles& triangles, int t, int label) {
  const int a = label / 2, b = (a + 1) % 3, c = (a + 2) % 3;
  const Eigen::RowVector3d e1 = p.row(triangles(t, 1)) - p.row(triangles(t, 0)),
                           e2 = p.row(triangles(t, 2)) - p.row(triangles(t, 0));
  return (e1[b] * e2[c] - e1[c] * e2[b]) * (label % 2 == 0 ? 1.0 : -1.0);
}

}  // namespace

StraightBoundaries straighten_boundaries(const PolygonMesh& input, const Vertices& polycube,
                                         const PolycubeSurface& surface, const std::array<AxisGrid, 3>& grid,
                                         double min_run) {
  StraightBoundaries out;
  out.polycube = polycube;
  const int n = static_cast<int>(polycube.rows());
  const PolygonFaces& faces = input.faces;
  const Triangles& triangles = surface.triangulation.triangles;
  const double h = grid[0].h;

  // Per vertex: the axes of the planes it lies on (it cannot leave them) and
  // whether it touches a collapsed face (it stays: no plane tells where it may go).
  std::vector<int> fixed_axes(n, 0);
  std::vector<char> pinned(n, 0);
  std::map<std::pair<int, int>, int> face_of_edge;  // directed edge -> its face
  for (int f = 0; f < faces.count(); ++f)
    for (int k = faces.offsets[f]; k < faces.offsets[f + 1]; ++k) {
      const int u = faces.indices[k], w = faces.indices[k + 1 < faces.offsets[f + 1] ? k + 1 : faces.offsets[f]];
      if (surface.face_carries_area[f])
        fixed_axes[u] |= 1 << (surface.face_label[f] / 2);
      else
        pinned[u] = 1;
      face_of_edge[{u, w}] = f;
    }
  std::vector<int> next(n, -1), boundary_face(n, -1);
  std::vector<char> branching(n, 0), on_boundary(n, 0);
  for (const auto& [edge, f] : face_of_edge)
    if (!face_of_edge.count({edge.second, edge.first})) {
      if (next[edge.first] >= 0) branching[edge.first] = 1;
      next[edge.first] = edge.second;
      boundary_face[edge.first] = f;
      on_boundary[edge.first] = on_boundary[edge.second] = 1;
    }

  std::vector<std::vector<int>> neighbours(n);
  {
    std::set<std::pair<int, int>> edges;
    for (Eigen::Index t = 0; t < triangles.rows(); ++t)
      for (int k = 0; k < 3; ++k) {
        const int u = triangles(t, k), w = triangles(t, (k + 1) % 3);
        edges.insert({std::min(u, w), std::max(u, w)});
      }
    for (const auto& [u, w] : edges) {
      neighbours[u].push_back(w);
      neighbours[w].push_back(u);
    }
  }

  // Where a triangle may go: one that carries area keeps its side and more than 1e-3 of its area
  // (a sliver with none of its own stays out of the remesh, whatever its shape).
  std::vector<double> before(triangles.rows(), 0.0);
  const double tiny = 1e-14 * surface.diagonal * surface.diagonal;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int f = surface.triangulation.face_of_triangle[t];
    if (!surface.face_carries_area[f]) continue;
    before[t] = flat_area2(polycube, triangles, static_cast<int>(t), surface.face_label[f]);
  }
  std::vector<int> counted(triangles.rows(), -1);  // per triangle its label where keeps_sides looks at it
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    if (before[t] > tiny) counted[t] = surface.face_label[surface.triangulation.face_of_triangle[t]];
  auto keeps_sides = [&](const Vertices& p) {
    for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
      if (counted[t] < 0) continue;
      const double after = flat_area2(p, triangles, static_cast<int>(t), counted[t]);
      if (!(after > 1e-3 * before[t])) return false;
    }
    return true;
  };

  // Per vertex of a loop: its move onto its runs and the axes that move sets (along a run it may slide).
  struct Move {
    Eigen::Vector3d d = Eigen::Vector3d::Zero();
    int held = 0;
  };
  // The harmonic displacement (uniform weights) of one loop's moves, per axis: held at the moves,
  // on the other boundaries, on the planes of that axis, at pinned vertices and beyond a reach of
  // the loop (four steps past its largest move: a loop's cost does not grow with the mesh).
  std::vector<int> source(n, -1);
  std::vector<int> near, free_axes(n, 0);  // of the last displacement: the coordinates it solved for
  auto displacement = [&](const std::map<int, Move>& moves) {
    Vertices field = Vertices::Zero(n, 3);
    double largest = 0.0;
    for (int v : near) free_axes[v] = 0;
    near.clear();
    for (const auto& [v, move] : moves) {
      largest = std::max(largest, move.d.norm());
      source[v] = v;
      near.push_back(v);
    }
    const double reach = 4.0 * h + 2.0 * largest;
    for (size_t head = 0; head < near.size(); ++head)
      for (int w : neighbours[near[head]])
        if (source[w] < 0 && (polycube.row(w) - polycube.row(source[near[head]])).norm() <= reach) {
          source[w] = source[near[head]];
          near.push_back(w);
        }
    for (int k = 0; k < 3; ++k) {
      std::vector<int> unknown(n, -1);
      Eigen::VectorXd held = Eigen::VectorXd::Zero(n);
      int count = 0;
      for (int v : near) {
        if (pinned[v] || (fixed_axes[v] & (1 << k))) continue;
        if (on_boundary[v]) {
          const auto move = moves.find(v);
          if (move == moves.end()) continue;
          held[v] = move->second.d[k];
          if (move->second.held & (1 << k)) continue;
        }
        unknown[v] = count++;
        free_axes[v] |= 1 << k;
      }
      if (held.isZero(0.0)) continue;
      std::vector<Eigen::Triplet<double>> entries;
      Eigen::VectorXd rhs = Eigen::VectorXd::Zero(count), x;
      for (int v : near) {
        if (unknown[v] < 0) continue;
        entries.emplace_back(unknown[v], unknown[v], static_cast<double>(neighbours[v].size()));
        for (int w : neighbours[v])
          if (unknown[w] >= 0)
            entries.emplace_back(unknown[v], unknown[w], -1.0);
          else
            rhs[unknown[v]] += held[w];
      }
      if (count > 0) {
        Eigen::SparseMatrix<double> matrix(count, count);
        matrix.setFromTriplets(entries.begin(), entries.end());
        SparseCholesky solver;
        solver.analyze(matrix);
        solver.factorize(matrix);
        x = solver.solve(rhs);
      }
      for (int v : near) field(v, k) = unknown[v] >= 0 ? x[unknown[v]] : held[v];
    }
    for (int v : near) source[v] = -1;
    return field;
  };

  std::vector<char> seen(n, 0);
  for (int start = 0; start < n; ++start) {
    if (next[start] < 0 || seen[start]) continue;
    std::vector<int> loop;
    bool usable = true;
    for (int v = start; v >= 0 && !seen[v]; v = next[v]) {
      seen[v] = 1;
      loop.push_back(v);
      usable &= !branching[v] && !pinned[v] && surface.face_carries_area[boundary_face[v]];
    }
    ++out.loops;
    if (!usable || loop.size() < 3 || next[loop.back()] != start) continue;
    const int m = static_cast<int>(loop.size());  // edge j: loop[j] -> loop[(j + 1) % m]
    std::vector<int> first_axis(m), chart_axis(m);
    std::vector<char> crossing(m, 0);
    std::vector<double> length(m);
    for (int j = 0; j < m; ++j) {
      const int a = surface.face_label[boundary_face[loop[j]]] / 2, b = (a + 1) % 3, c = (a + 2) % 3;
      const Eigen::RowVector3d d = polycube.row(loop[(j + 1) % m]) - polycube.row(loop[j]);
      chart_axis[j] = a;
      first_axis[j] = std::abs(d[b]) >= std::abs(d[c]) ? c : b;  // going along b: c stays
      // An edge at a polycube edge (a vertex on its chart's plane and one other) crosses it: it
      // keeps the coordinate along that edge, the one its vertex there may change.
      for (int v : {loop[j], loop[(j + 1) % m]}) {
        const int other = fixed_axes[v] & ~(1 << a);
        if ((fixed_axes[v] & (1 << a)) && other != 0 && (other & (other - 1)) == 0)
          first_axis[j] = 3 - a - (other == 1 ? 0 : other == 2 ? 1 : 2), crossing[j] = 1;
      }
      length[j] = d.norm();
    }
    std::vector<int> edge_axis;
    auto runs_of = [&]() {
      std::vector<Run> runs;
      int first = 0;
      while (first < m && edge_axis[first] == edge_axis[(first + m - 1) % m]) ++first;
      if (first == m) return std::vector<Run>{{0, m, edge_axis[0]}};
      for (int j = 0; j < m; ++j) {
        const int e = (first + j) % m;
        if (j == 0 || edge_axis[e] != runs.back().axis) runs.push_back({e, 0, edge_axis[e]});
        ++runs.back().count;
      }
      return runs;
    };
    // The spread of axis k's coordinates over the vertices of edges first .. first + count - 1.
    auto spread = [&](int first, int count, int k) {
      double low = INFINITY, high = -INFINITY;
      for (int j = 0; j <= count; ++j) {
        const double x = polycube(loop[(first + j) % m], k);
        low = std::min(low, x), high = std::max(high, x);
      }
      return high - low;
    };
    // The runs: edges by the axis they go along; short runs between two runs at one coordinate
    // join them where the three stay within ten steps of a line (a loop slantwise across a
    // chart becomes one run there, not a staircase: the larger move is opened by untangle_in_charts).
    std::vector<char> locked(m, 0);
    auto plan = [&](bool split_turns, double join_spread) {
      edge_axis = first_axis;
      std::fill(locked.begin(), locked.end(), 0);
      // A run that turns back within a chart (the boundary going along it and back, a hairpin)
      // would lay both ways onto one line: split_turns makes the edge after the turn (or the one
      // before, if that one crosses a polycube edge) go across instead, and keeps it so.
      if (split_turns)
        for (int j = 0; j < m; ++j) {
          const int i = (j + m - 1) % m, a = chart_axis[j], k = first_axis[j], s = 3 - a - k;
          if (chart_axis[i] != a || first_axis[i] != k) continue;
          const double before_s = polycube(loop[j], s) - polycube(loop[i], s),
                       after_s = polycube(loop[(j + 1) % m], s) - polycube(loop[j], s);
          if (before_s * after_s >= 0.0) continue;
          const int e = !crossing[j] ? j : !crossing[i] ? i : -1;
          if (e < 0) continue;
          edge_axis[e] = s;
          locked[e] = 1;
        }
      for (;;) {
        const std::vector<Run> runs = runs_of();
        if (runs.size() < 3) break;
        int best = -1;
        double best_length = min_run;
        for (size_t r = 0; r < runs.size(); ++r) {
          const Run& before = runs[(r + runs.size() - 1) % runs.size()];
          const Run& after = runs[(r + 1) % runs.size()];
          if (before.axis != after.axis) continue;
          double run_length = 0.0;
          bool allowed = true;
          for (int j = 0; j < runs[r].count; ++j) {
            run_length += length[(runs[r].first + j) % m];
            allowed &= chart_axis[(runs[r].first + j) % m] != before.axis && !locked[(runs[r].first + j) % m];
          }
          for (const Run* side : {&before, &after})  // a split turn stays a run of its own
            for (int j = 0; j < side->count; ++j) allowed &= !locked[(side->first + j) % m];
          const int joined = before.count + runs[r].count + after.count;
          if (!allowed || run_length >= best_length || joined > m ||
              spread(before.first, joined, before.axis) > join_spread * h)
            continue;
          best = static_cast<int>(r);
          best_length = run_length;
        }
        if (best < 0) break;
        const Run& r = runs[best];
        for (int j = 0; j < r.count; ++j) edge_axis[(r.first + j) % m] = runs[(best + 1) % runs.size()].axis;
      }
      // Every run onto the grid line nearest its mean (length-weighted), and not onto a plane of
      // the same axis (a chart's edge would meet the boundary there): one step off it, out of the surface.
      std::map<int, Move> moves;
      for (const Run& run : runs_of()) {
        const int k = run.axis;
        double inward = 0.0, sum = 0.0, weight = 0.0;
        for (int j = 0; j < run.count; ++j) {
          const int e = (run.first + j) % m, label = surface.face_label[boundary_face[loop[e]]];
          const Eigen::Vector3d normal = (label % 2 == 0 ? 1.0 : -1.0) * Eigen::Vector3d::Unit(label / 2);
          const Eigen::Vector3d d = (polycube.row(loop[(e + 1) % m]) - polycube.row(loop[e])).transpose();
          inward += normal.cross(d)[k];  // the surface lies left of the boundary, seen from outside
          sum += length[e] * 0.5 * (polycube(loop[e], k) + polycube(loop[(e + 1) % m], k));
          weight += length[e];
        }
        const double mean = weight > 0.0 ? sum / weight : polycube(loop[run.first], k);
        long step = std::lround(grid[k].to_grid(mean));
        // Nor past a plane of axis k that a vertex of the run neighbours (a polycube edge along
        // the run bounds its chart there): between the nearest such ones on either side, or no plan.
        double low = -INFINITY, high = INFINITY;  // in grid steps
        for (int j = 0; j <= run.count; ++j) {
          const int v = loop[(run.first + j) % m];
          for (int w : neighbours[v]) {
            if (!(fixed_axes[w] & (1 << k))) continue;
            const double at = grid[k].to_grid(polycube(w, k));
            if (polycube(w, k) <= polycube(v, k))
              low = std::max(low, at);
            else
              high = std::min(high, at);
          }
        }
        const auto& steps = grid[k].steps;
        auto off_planes = [&](long g) {
          return !std::binary_search(steps.begin(), steps.end(), g) ||
                 std::abs(grid[k].from_grid(static_cast<double>(g)) - mean) <= 1e-9 * h;
        };
        if (!off_planes(step)) step += inward >= 0.0 ? -1 : 1;
        if (step <= low) step = std::lround(std::floor(low)) + 1;
        if (step >= high) step = std::lround(std::ceil(high)) - 1;
        if (step <= low || step >= high || !off_planes(step)) return std::map<int, Move>{};
        const double target = grid[k].from_grid(static_cast<double>(step));
        for (int j = 0; j <= run.count; ++j) {
          const int v = loop[(run.first + j) % m];
          if (fixed_axes[v] & (1 << k)) return std::map<int, Move>{};  // it would leave its plane
          Move& move = moves[v];
          move.d[k] = target - polycube(v, k);
          move.held |= 1 << k;
        }
      }
      return moves;
    };
    // The grid lines the loop crosses within its charts: its staircase turns at about each.
    long crossings = 0;
    for (int j = 0; j < m; ++j)
      for (int k : {(chart_axis[j] + 1) % 3, (chart_axis[j] + 2) % 3})
        crossings += std::labs(std::lround(std::floor(grid[k].to_grid(polycube(loop[(j + 1) % m], k)))) -
                               std::lround(std::floor(grid[k].to_grid(polycube(loop[j], k)))));
    // A plan whose move cannot be opened again is tried once more with its turns split, then
    // with ever fewer runs joined (more corners, smaller moves), before the loop stays as it was;
    // such a plan only while its runs, a corner each, stay under two thirds of the staircase's
    // turns (pig's holes a grid square wide came out with more irregular vertices laid than not).
    for (const auto& [split_turns, join_spread] :
         {std::pair{false, 10.0}, {true, 10.0}, {true, 5.0}, {true, 2.0}, {true, 0.0}}) {
      const std::map<int, Move> moves = plan(split_turns, join_spread);
      if (moves.empty()) continue;
      if (split_turns && 3 * static_cast<long>(runs_of().size()) >= 2 * crossings) break;
      Vertices moved;
      try {
        moved = out.polycube + displacement(moves);
      } catch (const Error&) {
        break;  // a part with nothing to hold it: it stays
      }
      // A triangle with its three corners on one run is laid flat on its line (a sliver at the
      // boundary: the remesh leaves it out, as the polycube's own collapsed ones).
      std::vector<int> flattened;
      for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
        if (counted[t] < 0) continue;
        const int a = counted[t] / 2;
        for (int k : {(a + 1) % 3, (a + 2) % 3}) {
          bool on_line = true;
          for (int q = 0; q < 3 && on_line; ++q) {
            const auto move = moves.find(triangles(t, q));
            on_line = move != moves.end() && (move->second.held & (1 << k)) &&
                      std::abs(moved(triangles(t, q), k) - moved(triangles(t, 0), k)) <= 1e-9 * h;
          }
          if (on_line) {
            flattened.push_back(static_cast<int>(t));
            break;
          }
        }
      }
      std::vector<int> labels_before;
      for (int t : flattened) labels_before.push_back(std::exchange(counted[t], -1));
      // A move the harmonic field turns triangles over with: the same move, the triangles
      // opened inside their charts (the field's own coordinates free, the boundary's held).
      if (keeps_sides(moved) ||
          (untangle_in_charts(out.polycube, moved, triangles, counted, free_axes, 2e-3) && keeps_sides(moved))) {
        out.polycube = moved;
        ++out.straightened;
        break;
      }
      for (size_t i = 0; i < flattened.size(); ++i) counted[flattened[i]] = labels_before[i];
    }
  }
  return out;
}

}  // namespace polycube
