#include "mesh/decimate_charts.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <queue>
#include <string>
#include <tuple>
#include <utility>

#include "mesh/nearest_point_weights.h"
#include "mesh/sort_by_vertex.h"
#include "mesh/triangle_incidence.h"
#include "mesh/union_find.h"

namespace polycube {
namespace {

// A collapse that turns a triangle further than this bends its chart out of
// the shape the fine faces give it.
const double kMaxTurnCosine = std::cos(M_PI / 4);
// Below this fraction of the squared bounding-box diagonal a triangle's
// normal is rounding noise: such fine triangles pin their corners, and no
// collapse may make one.
constexpr double kMinAreaFraction = 1e-12;
constexpr double kInfinity = std::numeric_limits<double>::infinity();
// Weight of the point quadrics (squared distance to each fine vertex merged
// into a vertex) against the plane quadrics. On a flat chart every plane
// error is zero, and without them collapses pile onto one vertex until it has
// hundreds of slivers around it, each later collapse checking them all (a
// million-triangle CAD model took minutes instead of seconds); with them a
// vertex that has absorbed many costs more to absorb another, and flat
// charts coarsen evenly. Small enough that on a curved chart the planes
// decide once edges are a few hundredths of the radius of curvature long.
constexpr double kPointWeight = 1e-3;

// What a fine vertex may do. Seam vertices move only along their seam, so
// the boundary between their two charts (or their chart's open border) keeps
// its place; fixed vertices (three charts, non-manifold, on flat triangles)
// hold the corners and everything the rules cannot reason about.
enum class Kind : char { kInterior, kSeam, kFixed };

// The open border, as the second chart of a seam vertex or an edge.
constexpr int kOpenBorder = -1;
// The second chart of an edge with more than two triangles: no seam at all.
constexpr int kNonManifold = -2;

// Labels 0..5 are +X, -X, +Y, -Y, +Z, -Z, as in labels/axis.h; mesh/ comes
// before labels/ in the core's rooms, so the axis is spelled out here.
Eigen::Vector3d axis_of_label(int label) {
  Eigen::Vector3d axis = Eigen::Vector3d::Zero();
  axis[label / 2] = label % 2 == 0 ? 1.0 : -1.0;
  return axis;
}

bool has_corner(const std::array<int, 3>& corners, int v) {
  return corners[0] == v || corners[1] == v || corners[2] == v;
}

// Sum over planes of weight * (n.p + d)^2, as the symmetric 4x4 matrix's ten entries.
struct Quadric {
  double xx = 0, xy = 0, xz = 0, yy = 0, yz = 0, zz = 0, x = 0, y = 0, z = 0, c = 0;

  void add_plane(const Eigen::Vector3d& n, double d, double weight) {
    xx += weight * n.x() * n.x();
    xy += weight * n.x() * n.y();
    xz += weight * n.x() * n.z();
    yy += weight * n.y() * n.y();
    yz += weight * n.y() * n.z();
    zz += weight * n.z() * n.z();
    x += weight * n.x() * d;
    y += weight * n.y() * d;
    z += weight * n.z() * d;
    c += weight * d * d;
  }

  // weight * |p - q|^2.
  void add_point(const Eigen::Vector3d& q, double weight) {
    xx += weight, yy += weight, zz += weight;
    x -= weight * q.x(), y -= weight * q.y(), z -= weight * q.z();
    c += weight * q.squaredNorm();
  }

  Quadric& operator+=(const Quadric& o) {
    xx += o.xx, xy += o.xy, xz += o.xz, yy += o.yy, yz += o.yz, zz += o.zz;
    x += o.x, y += o.y, z += o.z, c += o.c;
    return *this;
  }

  double at(const Eigen::Vector3d& p) const {
    return xx * p.x() * p.x() + yy * p.y() * p.y() + zz * p.z() * p.z() +
           2 * (xy * p.x() * p.y() + xz * p.x() * p.z() + yz * p.y() * p.z()) +
           2 * (x * p.x() + y * p.y() + z * p.z()) + c;
  }
};

// A fine vertex's place among the charts: interior to chart `own`
// (other == own), on the seam of charts own and other (other may be
// kOpenBorder), or fixed.
struct Role {
  int own = -1, other = -1;
  Kind kind = Kind::kFixed;
};

// The charts and every vertex's role, computed once.
struct FineCharts {
  std::vector<int> chart;  // per triangle, numbered by lowest triangle
  int chart_count = 0;
  std::vector<Role> role;  // per vertex
  std::vector<std::array<int, 3>> open_edges;  // ends and triangle of each edge with one triangle
};

FineCharts charts_and_roles(const Vertices& vertices, const Triangles& triangles, const std::vector<int>& labels,
                       double min_area) {
  const int vertex_count = static_cast<int>(vertices.rows());
  const int triangle_count = static_cast<int>(triangles.rows());
  std::vector<char> fixed(vertex_count, 0), on_border(vertex_count, 0);
  std::vector<int> seam_edges(vertex_count, 0);

  std::vector<std::tuple<int, int, int>> sides;  // lower vertex, higher vertex, triangle
  sides.reserve(3 * static_cast<size_t>(triangle_count));
  for (int t = 0; t < triangle_count; ++t) {
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const Eigen::Vector3d pa = vertices.row(a), pb = vertices.row(b), pc = vertices.row(c);
    if (a == b || b == c || c == a || 0.5 * (pb - pa).cross(pc - pa).norm() <= min_area)
      fixed[a] = fixed[b] = fixed[c] = 1;
    for (int k = 0; k < 3; ++k) {
      const int p = triangles(t, k), q = triangles(t, (k + 1) % 3);
      if (p != q) sides.emplace_back(std::min(p, q), std::max(p, q), t);
    }
  }
  sort_by_vertex(sides, vertex_count);

  // Runs of one edge: [begin, end) in sides.
  std::vector<std::pair<int, int>> edges;
  for (size_t begin = 0, end; begin < sides.size(); begin = end) {
    end = begin + 1;
    while (end < sides.size() && std::get<0>(sides[end]) == std::get<0>(sides[begin]) &&
           std::get<1>(sides[end]) == std::get<1>(sides[begin]))
      ++end;
    edges.emplace_back(static_cast<int>(begin), static_cast<int>(end));
  }

  // Charts join only across manifold edges: an edge of three triangles
  // says nothing about which two belong together.
  UnionFind sets(triangle_count);
  for (const auto& [begin, end] : edges) {
    const auto [a, b, t] = sides[begin];
    if (end - begin > 2) fixed[a] = fixed[b] = 1;
    if (end - begin != 2) continue;
    const int s = std::get<2>(sides[begin + 1]);
    if (labels[t] == labels[s]) sets.join(t, s);
  }
  FineCharts fine;
  fine.chart.assign(triangle_count, -1);
  std::vector<int> id_of_root(triangle_count, -1);
  for (int t = 0; t < triangle_count; ++t) {
    const int root = sets.root(t);
    if (id_of_root[root] < 0) id_of_root[root] = fine.chart_count++;
    fine.chart[t] = id_of_root[root];
  }
  for (const auto& [begin, end] : edges) {
    const auto [a, b, t] = sides[begin];
    const bool open = end - begin == 1;
    if (open) {
      on_border[a] = on_border[b] = 1;
      fine.open_edges.push_back({a, b, t});
    }
    if (open || (end - begin == 2 && fine.chart[t] != fine.chart[std::get<2>(sides[begin + 1])])) {
      ++seam_edges[a];
      ++seam_edges[b];
    }
  }

  // A vertex may move only if its triangles form one fan: its link (the
  // edges opposite it) is one cycle, or one path on the open border.
  const TriangleIncidence incidence(vertex_count, triangles);
  fine.role.assign(vertex_count, Role());
  std::vector<int> link, charts_here;
  UnionFind link_sets;
  for (int v = 0; v < vertex_count; ++v) {
    const int first = incidence.offsets[v], count = incidence.offsets[v + 1] - first;
    if (count == 0 || fixed[v]) continue;
    link.clear();
    charts_here.clear();
    for (int i = first; i < first + count; ++i) {
      const int t = incidence.triangles[i];
      charts_here.push_back(fine.chart[t]);
      for (int k = 0; k < 3; ++k)
        if (triangles(t, k) != v) link.push_back(triangles(t, k));
    }
    std::sort(link.begin(), link.end());
    link.erase(std::unique(link.begin(), link.end()), link.end());
    const int link_count = static_cast<int>(link.size());
    if (count != link_count && count != link_count - 1) continue;
    link_sets.reset(link_count);
    int pieces = link_count;
    auto index = [&](int w) { return static_cast<int>(std::lower_bound(link.begin(), link.end(), w) - link.begin()); };
    for (int i = first; i < first + count; ++i) {
      const int t = incidence.triangles[i];
      int ends[2], e = 0;
      for (int k = 0; k < 3; ++k)
        if (triangles(t, k) != v) ends[e++] = index(triangles(t, k));
      if (link_sets.join(ends[0], ends[1])) --pieces;
    }
    if (pieces != 1) continue;
    std::sort(charts_here.begin(), charts_here.end());
    charts_here.erase(std::unique(charts_here.begin(), charts_here.end()), charts_here.end());
    if (charts_here.size() == 1 && !on_border[v]) {
      fine.role[v] = {charts_here[0], charts_here[0], Kind::kInterior};
    } else if (seam_edges[v] == 2 && charts_here.size() == 1 && on_border[v]) {
      fine.role[v] = {charts_here[0], kOpenBorder, Kind::kSeam};
    } else if (seam_edges[v] == 2 && charts_here.size() == 2 && !on_border[v]) {
      fine.role[v] = {charts_here[0], charts_here[1], Kind::kSeam};
    }
  }
  return fine;
}

// What the queue reads of a vertex next to one it looks at, together: a
// separate array each would be a cache miss each.
struct FineVertex {
  Eigen::Vector3d position;
  Role role;
};

// A fine vertex collapsed away, kept in the list of the coarse triangle it
// is homed in with all that placing it again reads: a collapse reads its
// points one after another instead of from all over the mesh.
struct HomedPoint {
  Eigen::Vector3d position;
  std::array<double, 3> barycentric;  // in the triangle's corners
  Role role;
  int point;
};

// A coarse triangle, in the slot of the fine triangle it was: the same
// triangle with some corners moved.
struct Slot {
  std::array<int, 3> corners;
  int chart, label;
  bool alive = true;
};

// A vertex in the queue, at (a lower bound of) its cheapest collapse; the
// target is found again when it comes out. The stamp tells whether this is
// the vertex's latest entry.
struct Candidate {
  double cost;
  int from;
  unsigned stamp;
};

// Cheapest on top; equal costs by vertex id (a vertex has one live entry),
// so runs repeat exactly.
struct CostlierCandidate {
  bool operator()(const Candidate& a, const Candidate& b) const {
    if (a.cost != b.cost) return a.cost > b.cost;
    if (a.from != b.from) return a.from > b.from;
    return a.stamp > b.stamp;
  }
};

struct Placement {
  int slot;
  HomedPoint point;
};

// A triangle around v after a collapse, with its corners' positions, which
// every point placed tries.
struct StarTriangle {
  int slot, chart;
  std::array<int, 3> corners;
  std::array<Eigen::Vector3d, 3> at;
};

// An edge of a StarTriangle: its corners i and j, the charts on its two sides.
struct StarEdge {
  int star_index, i, j;
  int chart, other_chart;  // other_chart may be kOpenBorder or kNonManifold
};

// A triangle across a merged edge vo from the triangle that vanishes, with
// bits for its corners opposite such edges: a seam point with coordinate 0
// there lies on an edge whose far side changes.
struct Beyond {
  int slot;
  unsigned far_corners;
};

class Decimator {
 public:
  Decimator(const Vertices& vertices, const Triangles& triangles, const std::vector<int>& labels, double min_area)
      : fine_triangles_(triangles), min_area_(min_area) {
    FineCharts fine = charts_and_roles(vertices, triangles, labels, min_area);
    const int vertex_count = static_cast<int>(vertices.rows());
    const int triangle_count = static_cast<int>(triangles.rows());
    vertex_.resize(vertex_count);
    for (int v = 0; v < vertex_count; ++v) {
      vertex_[v].position = vertices.row(v);
      vertex_[v].role = fine.role[v];
    }
    slot_.resize(triangle_count);
    homed_.resize(triangle_count);
    around_.resize(vertex_count);
    vertex_alive_.assign(vertex_count, 1);
    quadric_.resize(vertex_count);
    self_cost_.assign(vertex_count, 0.0);
    stamp_.assign(vertex_count, 0);
    queued_.assign(vertex_count, 0);
    queued_cost_.assign(vertex_count, 0.0);
    refused_cost_.assign(vertex_count, 0.0);
    refused_target_.assign(vertex_count, -1);
    chart_size_.assign(fine.chart_count, 0);
    live_triangles_ = triangle_count;
    for (int t = 0; t < triangle_count; ++t) {
      Slot& slot = slot_[t];
      slot.corners = {triangles(t, 0), triangles(t, 1), triangles(t, 2)};
      slot.chart = fine.chart[t];
      slot.label = labels[t];
      ++chart_size_[slot.chart];
      const auto& c = slot.corners;
      around_[c[0]].push_back(t);
      if (c[1] != c[0]) around_[c[1]].push_back(t);
      if (c[2] != c[0] && c[2] != c[1]) around_[c[2]].push_back(t);
      const Eigen::Vector3d a = vertices.row(c[0]), b = vertices.row(c[1]), d = vertices.row(c[2]);
      const Eigen::Vector3d normal = (b - a).cross(d - a);
      const double area = 0.5 * normal.norm();
      if (area <= min_area) continue;
      const Eigen::Vector3d n = normal.normalized();
      Quadric plane;
      plane.add_plane(n, -n.dot(a), area);
      for (int k = 0; k < 3; ++k) {
        quadric_[c[k]] += plane;
        quadric_[c[k]].add_point(vertex_[c[k]].position, kPointWeight * area);
      }
    }
    // Garland and Heckbert's border planes, square to the face through each
    // open edge: a flat chart's border is free in the planes of its faces,
    // and these keep collapses from cutting its corners.
    for (const auto& [a, b, t] : fine.open_edges) {
      const Eigen::Vector3d pa = position(a), pb = position(b), pc = position(slot_[t].corners[0]);
      const Eigen::Vector3d pd = position(slot_[t].corners[1]), pe = position(slot_[t].corners[2]);
      const Eigen::Vector3d normal = (pd - pc).cross(pe - pc);
      const Eigen::Vector3d across = (pb - pa).cross(normal);
      if (0.5 * normal.norm() <= min_area || across.norm() == 0.0) continue;
      const Eigen::Vector3d n = across.normalized();
      Quadric plane;
      plane.add_plane(n, -n.dot(pa), 0.5 * normal.norm());
      quadric_[a] += plane;
      quadric_[b] += plane;
    }
    for (int v = 0; v < vertex_count; ++v) self_cost_[v] = quadric_[v].at(vertex_[v].position);
    fine_chart_ = std::move(fine.chart);
  }

  void run(int target_triangles) {
    const int vertex_count = static_cast<int>(vertex_.size());
    // A collapse refused now may be allowed once its surroundings have
    // changed beyond the vertices looked at again after each collapse: go
    // round again until a round makes none.
    for (;;) {
      for (int v = 0; v < vertex_count; ++v) {
        refused_target_[v] = -1;
        const auto [cost, target] = cheapest_target(v);
        if (target >= 0) queue_at(v, cost);
      }
      int collapses = 0;
      while (live_triangles_ > target_triangles && !queue_.empty()) {
        const Candidate candidate = queue_.top();
        queue_.pop();
        const int u = candidate.from;
        if (!vertex_alive_[u] || candidate.stamp != stamp_[u]) continue;
        queued_[u] = 0;
        const auto [cost, v] = cheapest_target(u);
        if (v < 0) continue;
        // The entry was a lower bound; if the true cost is still cheapest,
        // go on rather than queue it again.
        if (cost > candidate.cost && !ahead_of_queue(cost, u)) {
          queue_at(u, cost);
        } else if (plan(u, v)) {
          apply(u, v);
          ++collapses;
        } else {
          refused_cost_[u] = cost;
          refused_target_[u] = v;
          const auto [next_cost, next] = cheapest_target(u);
          if (next >= 0) queue_at(u, next_cost);
        }
      }
      if (live_triangles_ <= target_triangles || collapses == 0) break;
    }
  }

  Decimation result() const {
    const int vertex_count = static_cast<int>(vertex_.size());
    const int triangle_count = static_cast<int>(slot_.size());
    Decimation d;
    std::vector<int> coarse_vertex(vertex_count, -1), coarse_triangle(triangle_count, -1);
    for (int v = 0; v < vertex_count; ++v)
      if (vertex_alive_[v]) {
        coarse_vertex[v] = static_cast<int>(d.kept.size());
        d.kept.push_back(v);
      }
    d.triangles.resize(live_triangles_, 3);
    for (int t = 0, next = 0; t < triangle_count; ++t) {
      if (!slot_[t].alive) continue;
      coarse_triangle[t] = next;
      for (int k = 0; k < 3; ++k) d.triangles(next, k) = coarse_vertex[slot_[t].corners[k]];
      d.labels.push_back(slot_[t].label);
      d.charts.push_back(slot_[t].chart);
      ++next;
    }
    d.fine_charts = fine_chart_;
    d.home.assign(vertex_count, -1);
    d.barycentric = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>::Zero(vertex_count, 3);
    for (int t = 0; t < triangle_count; ++t)
      for (const HomedPoint& homed : homed_[t]) {
        d.home[homed.point] = coarse_triangle[t];
        for (int k = 0; k < 3; ++k) d.barycentric(homed.point, k) = homed.barycentric[k];
      }
    for (int p = 0; p < vertex_count; ++p) {
      if (!around_[p].empty()) {
        const int t = *std::min_element(around_[p].begin(), around_[p].end());
        const auto& corners = slot_[t].corners;
        d.home[p] = coarse_triangle[t];
        d.barycentric(p, std::find(corners.begin(), corners.end(), p) - corners.begin()) = 1.0;
      }
    }
    d.face_home.resize(triangle_count);
    for (int t = 0; t < triangle_count; ++t) {
      std::array<int, 3> homes;
      for (int k = 0; k < 3; ++k) homes[k] = d.home[fine_triangles_(t, k)];
      int best = 0, best_count = 0;
      for (int k = 0; k < 3; ++k) {
        const int count = static_cast<int>(std::count(homes.begin(), homes.end(), homes[k]));
        if (count > best_count) best = k, best_count = count;
      }
      d.face_home[t] = homes[best];
    }
    return d;
  }

 private:
  const Eigen::Vector3d& position(int v) const { return vertex_[v].position; }
  Kind kind(int v) const { return vertex_[v].role.kind; }

  // The distinct vertices next to u, into `out`; a few, so a linear search
  // beats marks spread over the mesh.
  void neighbours_of(int u, std::vector<int>& out) const {
    out.clear();
    for (int t : around_[u])
      for (int w : slot_[t].corners)
        if (w != u && std::find(out.begin(), out.end(), w) == out.end()) out.push_back(w);
  }

  // u's neighbours into neighbours_, unless they are there already: a
  // popped vertex's are found for its target, then for its collapse's
  // checks, then for what the collapse changes.
  void find_neighbours(int u) {
    if (u == neighbours_owner_ && collapse_count_ == neighbours_at_collapse_) return;
    neighbours_of(u, neighbours_);
    neighbours_owner_ = u;
    neighbours_at_collapse_ = collapse_count_;
  }

  // Whether edge uw lies on u's own seam: between u's two charts, or on
  // the open border of u's chart.
  bool along_own_seam(int u, int w) const {
    int count = 0, charts[2] = {-1, -1};
    for (int t : around_[u])
      if (has_corner(slot_[t].corners, w)) {
        if (count < 2) charts[count] = slot_[t].chart;
        ++count;
      }
    const Role& role = vertex_[u].role;
    if (count == 1) return role.other == kOpenBorder && charts[0] == role.own;
    return count == 2 && role.other != kOpenBorder &&
           ((charts[0] == role.own && charts[1] == role.other) || (charts[0] == role.other && charts[1] == role.own));
  }

  bool ahead_of_queue(double cost, int u) const {
    if (queue_.empty()) return true;
    const Candidate& top = queue_.top();
    return cost < top.cost || (cost == top.cost && u < top.from);
  }

  bool may_target(int u, int w) const {
    return kind(u) == Kind::kInterior || (kind(u) == Kind::kSeam && along_own_seam(u, w));
  }

  double collapse_cost(int u, int w) const { return quadric_[u].at(position(w)) + self_cost_[w]; }

  // u's cheapest target after the ones it was refused, in the queue's order
  // (cost, then vertex id); {inf, -1} when there is none.
  std::pair<double, int> cheapest_target(int u) {
    if (!vertex_alive_[u] || kind(u) == Kind::kFixed) return {kInfinity, -1};
    find_neighbours(u);
    const int refused = refused_target_[u];
    const double refused_cost = refused < 0 ? -kInfinity : refused_cost_[u];
    double best_cost = kInfinity;
    int best = -1;
    for (int w : neighbours_) {
      if (!may_target(u, w)) continue;
      const double cost = collapse_cost(u, w);
      if (cost < refused_cost || (cost == refused_cost && w <= refused)) continue;
      if (cost < best_cost || (cost == best_cost && w < best)) best_cost = cost, best = w;
    }
    return {best_cost, best};
  }

  // Queued costs are lower bounds, checked when they come out: a cost that
  // only rose (a target's quadric grew, a target went) needs no new entry,
  // so the queue holds few stale ones.
  void queue_at(int u, double cost) {
    if (queued_[u] && queued_cost_[u] <= cost) return;
    queued_[u] = 1;
    queued_cost_[u] = cost;
    queue_.push({cost, u, ++stamp_[u]});
  }

  // After a collapse onto v, a vertex next to v may have a cheaper target
  // than its queued cost only if it has a new neighbour or lost a refusal.
  void requeue_after_change(int w, int new_neighbour) {
    if (refused_target_[w] >= 0) {
      refused_target_[w] = -1;
      const auto [cost, target] = cheapest_target(w);
      if (target >= 0) queue_at(w, cost);
    } else if (vertex_alive_[w] && may_target(w, new_neighbour)) {
      queue_at(w, collapse_cost(w, new_neighbour));
    }
  }

  int seam_edge_count(int u) {
    edge_ends_.clear();
    for (int t : around_[u])
      for (int w : slot_[t].corners)
        if (w != u) edge_ends_.emplace_back(w, slot_[t].chart);
    std::sort(edge_ends_.begin(), edge_ends_.end());
    int seams = 0;
    for (size_t begin = 0, end; begin < edge_ends_.size(); begin = end) {
      end = begin + 1;
      while (end < edge_ends_.size() && edge_ends_[end].first == edge_ends_[begin].first) ++end;
      if (end - begin == 1 || (end - begin == 2 && edge_ends_[begin].second != edge_ends_[begin + 1].second))
        ++seams;
    }
    return seams;
  }

  // Whether triangle t, with u moved to v, keeps a sound shape: not
  // flattened, not turned over or far round, not newly facing away from
  // its axis.
  bool stays_sound(int t, int u, int v) const {
    const auto& c = slot_[t].corners;
    std::array<Eigen::Vector3d, 3> p{position(c[0]), position(c[1]), position(c[2])};
    const Eigen::Vector3d before = (p[1] - p[0]).cross(p[2] - p[0]);
    for (int k = 0; k < 3; ++k)
      if (c[k] == u) p[k] = position(v);
    const Eigen::Vector3d after = (p[1] - p[0]).cross(p[2] - p[0]);
    const double before_norm = before.norm(), after_norm = after.norm();
    if (0.5 * after_norm <= min_area_ || before_norm == 0.0) return false;
    if (before.dot(after) <= kMaxTurnCosine * before_norm * after_norm) return false;
    const Eigen::Vector3d axis = axis_of_label(slot_[t].label);
    return axis.dot(after) / after_norm >= std::min(0.0, axis.dot(before) / before_norm);
  }

  bool is_vanishing(int t) const { return std::find(vanishing_.begin(), vanishing_.end(), t) != vanishing_.end(); }

  // Checks every rule for moving u onto v and, when they hold, leaves in
  // the scratch members what apply() does.
  bool plan(int u, int v) {
    vanishing_.clear();
    moved_.clear();
    for (int t : around_[u]) (has_corner(slot_[t].corners, v) ? vanishing_ : moved_).push_back(t);
    if (!keeps_topology(u, v)) return false;
    for (int t : moved_)
      if (!stays_sound(t, u, v)) return false;
    if (!keeps_charts(v)) return false;
    star_.clear();
    for (int s : around_[v])
      if (!is_vanishing(s)) add_to_star(s, u, v);
    for (int s : moved_) add_to_star(s, u, v);
    star_edges_built_ = false;
    return place_points(u, v);
  }

  // u may move only along its kind's edges, and the surface must stay a
  // surface: no pinch, no doubled face.
  bool keeps_topology(int u, int v) {
    if (vanishing_.empty() || vanishing_.size() > 2) return false;
    if (kind(u) == Kind::kInterior) {
      if (vanishing_.size() == 1) return false;
    } else if (!along_own_seam(u, v) || seam_edge_count(u) != 2) {
      return false;
    }
    opposite_.clear();
    for (int t : vanishing_)
      for (int w : slot_[t].corners)
        if (w != u && w != v) opposite_.push_back(w);
    if (opposite_.size() != vanishing_.size() || (opposite_.size() == 2 && opposite_[0] == opposite_[1]))
      return false;

    // Link condition: the only vertices next to both u and v are those
    // opposite edge uv, or the collapse pinches the surface.
    find_neighbours(u);
    neighbours_of(v, common_);
    common_.erase(std::remove_if(common_.begin(), common_.end(),
                                 [&](int w) {
                                   return w == u || std::find(neighbours_.begin(), neighbours_.end(), w) ==
                                                        neighbours_.end();
                                 }),
                  common_.end());
    if (common_.size() != opposite_.size()) return false;

    // Triangle (u, a, b) onto an existing (v, a, b), both a and b common.
    auto is_common = [&](int w) { return std::find(common_.begin(), common_.end(), w) != common_.end(); };
    for (int t : moved_) {
      int others[2], count = 0;
      for (int w : slot_[t].corners)
        if (w != u) others[count++] = w;
      if (is_common(others[0]) && is_common(others[1]))
        for (int s : around_[v])
          if (!is_vanishing(s) && has_corner(slot_[s].corners, others[0]) && has_corner(slot_[s].corners, others[1]))
            return false;
    }
    return true;
  }

  // Every chart keeps a triangle, every vertex of the vanishing triangles
  // keeps every chart it touched (so it stays on their planes), and no two
  // charts of one label come to share an edge (they would merge). Notes
  // the triangles beyond the merged edges for place_points().
  bool keeps_charts(int v) {
    beyond_.clear();
    for (size_t k = 0; k < vanishing_.size(); ++k) {
      const int t = vanishing_[k], o = opposite_[k], c = slot_[t].chart;
      const int lost = 1 + (vanishing_.size() == 2 && slot_[vanishing_[1 - k]].chart == c ? 1 : 0);
      if (chart_size_[c] <= lost) return false;
      auto keeps_chart = [&](int w) {
        for (int s : around_[w])
          if (!is_vanishing(s) && slot_[s].chart == c) return true;
        if (w == v)
          for (int s : moved_)
            if (slot_[s].chart == c) return true;
        return false;
      };
      if (!keeps_chart(v) || !keeps_chart(o)) return false;
      // Edges uo and vo become one, with the triangles of both.
      int merged[3], merged_count = 0;
      for (int s : around_[v])
        if (has_corner(slot_[s].corners, o) && !is_vanishing(s)) {
          if (merged_count < 3) merged[merged_count] = s;
          ++merged_count;
          note_beyond(s, v, o);
        }
      for (int s : moved_)
        if (has_corner(slot_[s].corners, o)) {
          if (merged_count < 3) merged[merged_count] = s;
          ++merged_count;
        }
      if (merged_count == 0 || merged_count > 2) return false;
      if (merged_count == 2 && slot_[merged[0]].chart != slot_[merged[1]].chart &&
          slot_[merged[0]].label == slot_[merged[1]].label)
        return false;
    }
    return true;
  }

  void note_beyond(int s, int v, int o) {
    unsigned far = 0;
    for (int k = 0; k < 3; ++k)
      if (slot_[s].corners[k] != v && slot_[s].corners[k] != o) far |= 1u << k;
    for (Beyond& b : beyond_)
      if (b.slot == s) {
        b.far_corners |= far;
        return;
      }
    beyond_.push_back({s, far});
  }

  static bool on_changed_edge(const HomedPoint& point, const Beyond& b) {
    if (point.role.kind != Kind::kSeam) return false;
    for (int k = 0; k < 3; ++k)
      if ((b.far_corners >> k & 1u) && point.barycentric[k] == 0.0) return true;
    return false;
  }

  void add_to_star(int s, int u, int v) {
    StarTriangle triangle{s, slot_[s].chart, slot_[s].corners, {}};
    for (int k = 0; k < 3; ++k) {
      if (triangle.corners[k] == u) triangle.corners[k] = v;
      triangle.at[k] = position(triangle.corners[k]);
    }
    star_.push_back(triangle);
  }

  // Homes for every fine vertex the collapse disturbs: u itself, those in
  // triangles around u, and seam points on an edge vo that gets a new
  // triangle on its far side. All are tried before anything changes.
  bool place_points(int u, int v) {
    points_.clear();
    placements_.clear();
    points_.push_back({position(u), {0, 0, 0}, vertex_[u].role, u});
    for (int t : around_[u]) points_.insert(points_.end(), homed_[t].begin(), homed_[t].end());
    for (const Beyond& b : beyond_)
      for (const HomedPoint& point : homed_[b.slot])
        if (on_changed_edge(point, b)) points_.push_back(point);
    for (const HomedPoint& point : points_)
      if (!place(point, v)) return false;
    return true;
  }

  // The point nearest the fine vertex's own position on what it may lie
  // on around v after the collapse: its chart's triangles, or the edges
  // of its own seam. Nearest to where it was in the fine mesh, not to
  // where it is now, so homes do not drift collapse after collapse.
  bool place(const HomedPoint& point, int v) {
    const Eigen::Vector3d& x = point.position;
    const Role& role = point.role;
    double best = kInfinity;
    Placement placement{-1, point};
    auto consider = [&](const StarTriangle& triangle, const std::array<double, 3>& b) {
      const Eigen::Vector3d y = b[0] * triangle.at[0] + b[1] * triangle.at[1] + b[2] * triangle.at[2];
      const double distance = (y - x).squaredNorm();
      if (distance < best) {
        best = distance;
        placement.slot = triangle.slot;
        placement.point.barycentric = b;
      }
    };
    if (role.kind == Kind::kInterior) {
      for (const StarTriangle& triangle : star_)
        if (triangle.chart == role.own) {
          const Eigen::Vector3d w = nearest_point_weights(x, triangle.at[0], triangle.at[1], triangle.at[2]);
          consider(triangle, {w[0], w[1], w[2]});
        }
    } else {
      build_star_edges(v);
      for (const StarEdge& e : star_edges_) {
        const bool on_own_seam = role.other == kOpenBorder
                                     ? e.other_chart == kOpenBorder && e.chart == role.own
                                     : (e.chart == role.own && e.other_chart == role.other) ||
                                           (e.chart == role.other && e.other_chart == role.own);
        if (!on_own_seam) continue;
        const StarTriangle& triangle = star_[e.star_index];
        const Eigen::Vector3d& a = triangle.at[e.i];
        const Eigen::Vector3d& b = triangle.at[e.j];
        const double length2 = (b - a).squaredNorm();
        const double t = length2 > 0 ? std::clamp((x - a).dot(b - a) / length2, 0.0, 1.0) : 0.0;
        std::array<double, 3> barycentric{0, 0, 0};
        barycentric[e.i] = 1 - t;
        barycentric[e.j] = t;
        consider(triangle, barycentric);
      }
    }
    if (placement.slot < 0) return false;
    placements_.push_back(placement);
    return true;
  }

  // The charts on both sides of every edge of the triangles around v after
  // the collapse. Edges at v have both their triangles in the star; an
  // edge opposite v is untouched, its far triangle found around one end.
  void build_star_edges(int v) {
    if (star_edges_built_) return;
    star_edges_built_ = true;
    star_edges_.clear();
    for (size_t i = 0; i < star_.size(); ++i) {
      const StarTriangle& triangle = star_[i];
      for (int k = 0; k < 3; ++k) {
        const int a = triangle.corners[k], b = triangle.corners[(k + 1) % 3];
        int count = 0, other_chart = kOpenBorder;
        if (a == v || b == v) {
          for (size_t j = 0; j < star_.size(); ++j)
            if (j != i && has_corner(star_[j].corners, a) && has_corner(star_[j].corners, b)) {
              ++count;
              other_chart = star_[j].chart;
            }
        } else {
          for (int s : around_[a])
            if (s != triangle.slot && has_corner(slot_[s].corners, b)) {
              ++count;
              other_chart = slot_[s].chart;
            }
        }
        if (count > 1) other_chart = kNonManifold;
        star_edges_.push_back({static_cast<int>(i), k, (k + 1) % 3, triangle.chart, other_chart});
      }
    }
  }

  void apply(int u, int v) {
    find_neighbours(u);
    changed_ = neighbours_;
    ++collapse_count_;
    for (size_t k = 0; k < vanishing_.size(); ++k) {
      const int t = vanishing_[k];
      slot_[t].alive = false;
      --live_triangles_;
      --chart_size_[slot_[t].chart];
      for (int w : {v, opposite_[k]}) {
        auto& list = around_[w];
        list.erase(std::find(list.begin(), list.end(), t));
      }
      std::vector<HomedPoint>().swap(homed_[t]);
    }
    for (int t : moved_) {
      for (int& w : slot_[t].corners)
        if (w == u) w = v;
      around_[v].push_back(t);
      homed_[t].clear();
    }
    for (const Beyond& b : beyond_) {
      auto& list = homed_[b.slot];
      list.erase(std::remove_if(list.begin(), list.end(),
                                [&](const HomedPoint& point) { return on_changed_edge(point, b); }),
                 list.end());
    }
    std::vector<int>().swap(around_[u]);
    vertex_alive_[u] = 0;
    for (const Placement& placement : placements_) homed_[placement.slot].push_back(placement.point);
    quadric_[v] += quadric_[u];
    self_cost_[v] = quadric_[v].at(position(v));
    // u's neighbours now neighbour v, and v them; every other cost either
    // stayed or rose (v's quadric grew).
    for (int w : changed_)
      if (w != v) {
        requeue_after_change(w, v);
        requeue_after_change(v, w);
      }
  }

  const Triangles& fine_triangles_;
  const double min_area_;

  std::vector<FineVertex> vertex_;
  std::vector<char> vertex_alive_;           // whether the vertex is still a coarse vertex
  std::vector<std::vector<int>> around_;     // live slots per live vertex
  std::vector<Slot> slot_;
  std::vector<std::vector<HomedPoint>> homed_;  // fine vertices homed per slot
  std::vector<int> fine_chart_;              // per fine triangle
  std::vector<int> chart_size_;              // live slots per chart
  int live_triangles_ = 0;

  std::vector<Quadric> quadric_;
  std::vector<double> self_cost_;  // each vertex's quadric at its own position
  std::priority_queue<Candidate, std::vector<Candidate>, CostlierCandidate> queue_;
  std::vector<unsigned> stamp_;
  std::vector<char> queued_;  // whether the vertex has a live entry
  std::vector<double> queued_cost_;
  // Targets up to (refused_cost_, refused_target_) in the queue's order were
  // refused; -1 for none. Cleared when the vertex's surroundings change.
  std::vector<double> refused_cost_;
  std::vector<int> refused_target_;

  // Scratch of plan() for apply(), kept to avoid allocating per collapse.
  std::vector<int> vanishing_, moved_, opposite_, neighbours_, common_, changed_;
  int neighbours_owner_ = -1;
  long collapse_count_ = 0, neighbours_at_collapse_ = -1;
  std::vector<HomedPoint> points_;
  std::vector<Beyond> beyond_;
  std::vector<StarTriangle> star_;
  std::vector<StarEdge> star_edges_;
  bool star_edges_built_ = false;
  std::vector<Placement> placements_;
  std::vector<std::pair<int, int>> edge_ends_;
};

void check_decimation_input(const Vertices& vertices, const Triangles& triangles, const std::vector<int>& labels,
                            int target_triangles) {
  if (target_triangles < 1)
    throw Error("the target triangle count must be at least 1, got " + std::to_string(target_triangles));
  if (static_cast<Eigen::Index>(labels.size()) != triangles.rows())
    throw Error("there are " + std::to_string(labels.size()) + " labels for " + std::to_string(triangles.rows()) +
                " triangles; give one label per triangle");
  for (size_t t = 0; t < labels.size(); ++t)
    if (labels[t] < 0 || labels[t] > 5)
      throw Error("triangle " + std::to_string(t) + " has label " + std::to_string(labels[t]) +
                  ", outside 0..5 (+X, -X, +Y, -Y, +Z, -Z); decimation needs every face labelled");
  for (Eigen::Index v = 0; v < vertices.rows(); ++v)
    if (!vertices.row(v).allFinite())
      throw Error("vertex " + std::to_string(v) + " has a non-finite coordinate (NaN or Inf)");
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles(t, k) < 0 || triangles(t, k) >= vertices.rows())
        throw Error("triangle " + std::to_string(t) + " uses vertex index " + std::to_string(triangles(t, k)) +
                    ", but the mesh has only " + std::to_string(vertices.rows()) + " vertices");
}

}  // namespace

Decimation decimate_charts(const Vertices& vertices, const Triangles& triangles, const std::vector<int>& labels,
                           int target_triangles) {
  check_decimation_input(vertices, triangles, labels, target_triangles);
  double diagonal2 = 0.0;
  if (vertices.rows() > 0) diagonal2 = (vertices.colwise().maxCoeff() - vertices.colwise().minCoeff()).squaredNorm();
  Decimator decimator(vertices, triangles, labels, kMinAreaFraction * diagonal2);
  decimator.run(target_triangles);
  return decimator.result();
}

Vertices carry_to_fine(const Decimation& decimation, const Vertices& coarse_positions) {
  if (coarse_positions.rows() != static_cast<Eigen::Index>(decimation.kept.size()))
    throw Error("there are " + std::to_string(coarse_positions.rows()) + " coarse positions for " +
                std::to_string(decimation.kept.size()) + " coarse vertices");
  const Eigen::Index fine_count = static_cast<Eigen::Index>(decimation.home.size());
  Vertices fine(fine_count, 3);
  for (Eigen::Index p = 0; p < fine_count; ++p) {
    const int home = decimation.home[p];
    if (home >= 0) {
      fine.row(p) = decimation.barycentric(p, 0) * coarse_positions.row(decimation.triangles(home, 0)) +
                    decimation.barycentric(p, 1) * coarse_positions.row(decimation.triangles(home, 1)) +
                    decimation.barycentric(p, 2) * coarse_positions.row(decimation.triangles(home, 2));
    } else {
      // A vertex in no triangle is kept as it is.
      const auto kept = std::lower_bound(decimation.kept.begin(), decimation.kept.end(), static_cast<int>(p));
      fine.row(p) = coarse_positions.row(kept - decimation.kept.begin());
    }
  }
  return fine;
}

}  // namespace polycube
