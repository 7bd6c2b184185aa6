#include "deform/polish_stage.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <limits>
#include <optional>
#include <utility>
#include <vector>

#include "deform/chart_planes.h"
#include "deform/robust_run.h"
#include "labels/axis.h"
#include "linear_algebra/parallel.h"
#include "linear_algebra/run_tasks.h"
#include "mesh/sort_by_vertex.h"
#include "mesh/triangle_incidence.h"

namespace polycube {
namespace {

// How far the polish may stretch or shrink a triangle: its area over its
// input area times the run's scale s^2 (held at the run's, so that a
// triangle whose corners stand still stays in bounds as the mesh's total
// area moves).
struct AreaBounds {
  double scale2 = 1.0, smallest = 0.0, largest = 0.0;
};

// What the step control walks, built once per polish: per axis, the
// vertices of each unknown (whose share a halving changes: only they move),
// and per vertex its triangles (only they change shape).
struct BlendIndex {
  std::array<std::vector<int>, 3> first, vertices;  // vertices[first[u] .. first[u + 1]) share unknown u
  TriangleIncidence incidence;

  BlendIndex(const Deformation& d, const ChartPlanes& planes) : incidence(d.n, d.triangles()) {
    for (int axis = 0; axis < 3; ++axis) {
      const std::vector<int>& unknown = planes.unknowns(axis);
      const int count = unknown.empty() ? 0 : *std::max_element(unknown.begin(), unknown.end()) + 1;
      first[axis].assign(count + 1, 0);
      for (int u : unknown) ++first[axis][u + 1];
      for (int u = 0; u < count; ++u) first[axis][u + 1] += first[axis][u];
      vertices[axis].resize(unknown.size());
      std::vector<int> next(first[axis].begin(), first[axis].end() - 1);
      for (int v = 0; v < static_cast<int>(unknown.size()); ++v) vertices[axis][next[unknown[v]]++] = v;
    }
  }
};

// Per triangle, a bit per axis in which its corners share one unknown (so
// one share), stand at one value and move in one direction (a chart's plane,
// inside the chart): whatever the step's length and share, that coordinate's
// differences stay exactly zero, so moving it changes neither the area nor
// the orientation. A halved plane moves every vertex of its chart, but only
// the triangles across the chart's edge change. Made once a descent step, for
// all its trials.
std::vector<char> rigid_axes(const Deformation& d, const ChartPlanes& planes, const Vertices& direction) {
  const Triangles& triangles = d.triangles();
  const Eigen::Index count = triangles.rows();
  std::vector<char> rigid(count, 0);
  run_in_parts(count, loop_parts(count), [&](long begin, long end) {
    for (Eigen::Index t = begin; t < end; ++t)
      for (int axis = 0; axis < 3; ++axis) {
        const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
        const std::vector<int>& unknown = planes.unknowns(axis);
        if (unknown[a] == unknown[b] && unknown[a] == unknown[c] && d.x(a, axis) == d.x(b, axis) &&
            d.x(a, axis) == d.x(c, axis) && direction(a, axis) == direction(b, axis) &&
            direction(a, axis) == direction(c, axis))
          rigid[t] |= static_cast<char>(1 << axis);
      }
  });
  return rigid;
}

// From the run's positions (whose triangle areas are `areas_now`) towards
// `target` (flat on the same charts), every
// unknown of `planes` with its own share of the step (none for the `held`
// vertices'): the shares of the unknowns around a triangle that blocks
// (turns over, stretches past its bound, or, unless the run left it
// collapsed, shrinks past it) are halved, and after kMaxHalvings halvings
// zeroed, until nothing blocks. The bounds hold at the run's scale, so a
// triangle whose corners stand still never blocks; the turn-over test is the
// figures' own, and a triangle the run left collapsed that opens turned over
// can block with its corners still: after that many rounds the step is
// dropped.
// After the first round only what a halving moves is measured again: the
// vertices of the unknowns halved, their triangles, and the triangles whose
// area points against their axis (the only ones the scale, which every
// move changes, can turn over); the rest of the mesh stands where the last
// round put it, with the same flags (the same result bit for bit as a
// measure of the whole mesh every round). With `signed_areas`, the blend's
// triangle areas signed along their axes, bit for bit as axis_areas() gives
// them, when it returns the blend: its errors need not measure them again.
Vertices controlled_blend(const Deformation& d, const ChartPlanes& planes, const BlendIndex& index,
                          const std::vector<char>& rigid, Vertices target, const std::vector<char>& collapsed_before,
                          const AreaBounds& bounds, const std::vector<char>& held, const std::vector<double>& areas_now,
                          std::vector<double>* signed_areas = nullptr) {
  const Triangles& triangles = d.triangles();
  const Eigen::Index count = triangles.rows();
  // In the target's memory: a vertex's worth less at the polish's peak.
  Vertices& step = target;
  step -= d.x;
  std::array<std::vector<double>, 3> share;
  std::array<std::vector<int>, 3> halvings;
  std::array<std::vector<char>, 3> marked;
  for (int axis = 0; axis < 3; ++axis) {
    const int unknowns = static_cast<int>(index.first[axis].size()) - 1;
    share[axis].assign(unknowns, 1.0);
    halvings[axis].assign(unknowns, 0);
    marked[axis].assign(unknowns, 0);
    for (int v = 0; v < d.n; ++v)
      if (held[v]) share[axis][planes.unknowns(axis)[v]] = 0.0;
  }
  Vertices next(d.n, 3);
  for (int v = 0; v < d.n; ++v)
    for (int axis = 0; axis < 3; ++axis)
      next(v, axis) = d.x(v, axis) + share[axis][planes.unknowns(axis)[v]] * step(v, axis);
  TriangleAreas measured;
  std::vector<char> unused_collapsed, flipped;
  d.quality.fold_flags(next, measured, unused_collapsed, flipped);
  const std::vector<double>& areas = measured.area;
  const std::vector<double>& input_areas = d.quality.input_areas();
  // Turned over, or its area further out of bounds than it is now (a
  // triangle at a bound stays there however rounding moves it).
  auto blocks = [&](Eigen::Index t) {
    const double ratio = areas[t] / (bounds.scale2 * input_areas[t]);
    const bool out =
        input_areas[t] > 0.0 && ((ratio > bounds.largest && areas[t] > areas_now[t]) ||
                                 (!collapsed_before[t] && ratio < bounds.smallest && areas[t] < areas_now[t]));
    return flipped[t] || out;
  };
  // The triangles blocking, and those pointing against their axis; a
  // triangle measured again this round is flagged in `seen`.
  std::vector<int> blocking, against, still, moved, moved_vertices, list;
  std::vector<char> seen(count, 0), vertex_moved(d.n, 0);  // per vertex, a bit per axis it moved in
  for (Eigen::Index t = 0; t < count; ++t) {
    if (measured.along[t] < 0.0) against.push_back(static_cast<int>(t));
    if (blocks(t)) blocking.push_back(static_cast<int>(t));
  }
  const int max_rounds = 4 * (kMaxHalvings + 1);
  std::array<std::vector<int>, 3> halved;
  for (int round = 1;; ++round) {
    if (blocking.empty()) {
      if (signed_areas) {
        // Half the doubled normal's component along the axis, as axis_areas() takes it.
        *signed_areas = std::move(measured.along);
        for (double& a : *signed_areas) a *= 0.5;
      }
      return next;
    }
    if (round == max_rounds) return d.x;
    for (int t : blocking)
      for (int k = 0; k < 3; ++k)
        for (int axis = 0; axis < 3; ++axis) {
          const int u = planes.unknowns(axis)[triangles(t, k)];
          if (!marked[axis][u]) halved[axis].push_back(u);
          marked[axis][u] = 1;
        }
    moved_vertices.clear();
    for (int axis = 0; axis < 3; ++axis) {
      for (int u : halved[axis]) {
        marked[axis][u] = 0;
        const double before = share[axis][u];
        share[axis][u] = ++halvings[axis][u] > kMaxHalvings ? 0.0 : 0.5 * share[axis][u];
        if (share[axis][u] == before) continue;
        for (int i = index.first[axis][u]; i < index.first[axis][u + 1]; ++i) {
          const int v = index.vertices[axis][i];
          const double value = d.x(v, axis) + share[axis][u] * step(v, axis);
          if (value == next(v, axis)) continue;
          next(v, axis) = value;
          if (!vertex_moved[v]) moved_vertices.push_back(v);
          vertex_moved[v] |= static_cast<char>(1 << axis);
        }
      }
      halved[axis].clear();
    }
    moved.clear();
    for (int v : moved_vertices) {
      const char axes = vertex_moved[v];
      vertex_moved[v] = 0;
      for (int i = index.incidence.offsets[v]; i < index.incidence.offsets[v + 1]; ++i) {
        const int t = index.incidence.triangles[i];
        if (!(axes & ~rigid[t])) continue;
        if (!seen[t]) moved.push_back(t);
        seen[t] = 1;
      }
    }
    const double scale2 = d.quality.rescale_moved(next, moved, measured);
    // Pointing against their axis now: those that did and stood still, and
    // the moved ones that do (the moved are flagged in `seen`).
    still.clear();
    for (int t : against)
      if (!seen[t]) still.push_back(t);
    for (int t : moved)
      if (measured.along[t] < 0.0) still.push_back(t);
    // The flags that can have changed (the moved triangles', and at the new
    // scale those pointing against their axis) and those that blocked.
    list = moved;
    for (const std::vector<int>* more : {&still, &blocking})
      for (int t : *more) {
        if (!seen[t]) list.push_back(t);
        seen[t] = 1;
      }
    blocking.clear();
    for (int t : list) {
      seen[t] = 0;
      flipped[t] = d.quality.turned_over(measured, t, scale2);
      if (blocks(t)) blocking.push_back(t);
    }
    against.swap(still);
  }
}

// The figures' two errors (docs/design.md section 4) as a smooth energy:
// the mean over edges of rho(log(l / (s l0))) and over triangles of
// rho(log(A / (s^2 A0))), rho(u) = sqrt(u^2 + kSmoothing^2) ~ |u|, A the
// area signed along the triangle's axis and s^2 the output area over the
// input's, itself a function of the positions (a step that only rescales
// gains nothing). Absolute values, as the figures: squares would trade many
// small errors for a few large ones. Logarithms, unlike the figures' plain
// ratios: |ratio - 1| is at most 1 for a shrinking triangle, so an energy
// of those gains by sacrificing a few triangles to near collapse (the
// eight's polycube UVs went from 2.2 to 8.6 in angle distortion); a
// logarithm grows without bound as a triangle or edge shrinks to nothing.
// What the run left collapsed (`left_out`, and edges of no length) is not
// counted.
constexpr double kSmoothing = 1e-3;

double rho(double u) { return std::sqrt(u * u + kSmoothing * kSmoothing); }  // its slope: u / rho(u)

// The smooth errors, and the figures' own (quality.h), measured in the same pass.
struct Errors {
  static constexpr double kNone = std::numeric_limits<double>::infinity();
  double edge = kNone, area = kNone, figure_edge = kNone, figure_area = kNone;
  // Neither smooth error larger than `other`'s, their sum smaller by at
  // least kPolishStall of it (polish_stage.h: a step worth taking).
  bool better_than(const Errors& other) const {
    const double sum = edge + area, other_sum = other.edge + other.area;
    return edge <= other.edge && area <= other.area && sum < other_sum && other_sum - sum >= kPolishStall * other_sum;
  }
  // Neither figure larger than `other`'s, their sum smaller.
  bool better_figures_than(const Errors& other) const {
    return figure_edge <= other.figure_edge && figure_area <= other.figure_area &&
           figure_edge + figure_area < other.figure_edge + other.figure_area;
  }
};

struct LeftOut {
  std::vector<char> triangles, edges;
};

// The logarithms of the input's edge lengths, taken once for every
// evaluation (0 for an edge of no length, which is not counted).
std::vector<double> log_lengths_of(const QualityMeasure& q) {
  const std::vector<double>& lengths = q.input_lengths();
  std::vector<double> logs(lengths.size(), 0.0);
  for (size_t e = 0; e < lengths.size(); ++e)
    if (lengths[e] > 0.0) logs[e] = std::log(lengths[e]);
  return logs;
}

// What the errors' gradients need of one evaluation of them: per edge the
// factor of its vector (NaN where the edge is not counted), per triangle the
// area error's derivative by its area A at fixed s^2, and each error's
// derivative by s^2. Kept so that only a trial that is taken pays for its
// gradients (about half of B0's trials are not).
struct Slopes {
  std::vector<double> edge, by_area;
  std::array<double, 2> by_scale = {0.0, 0.0};
};

// The triangles' areas signed along their axes, and their sum; with
// `unsigned_total`, the sum of their plain areas too.
double axis_areas(const Deformation& d, const Vertices& x, std::vector<double>& area,
                  double* unsigned_total = nullptr) {
  const Triangles& triangles = d.triangles();
  area.resize(triangles.rows());
  double total = 0.0, plain = 0.0;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const Eigen::Vector3d pa = x.row(triangles(t, 0)), pb = x.row(triangles(t, 1)), pc = x.row(triangles(t, 2));
    const Eigen::Vector3d normal = (pb - pa).cross(pc - pa);
    area[t] = 0.5 * normal.dot(label_axis(d.triangle_labels[t]));
    total += area[t];
    if (unsigned_total) plain += 0.5 * normal.norm();
  }
  if (unsigned_total) *unsigned_total = plain;
  return total;
}

// With `slopes`, what smooth_gradients() needs too. `log_lengths`:
// log_lengths_of(d.quality). With `beat`, errors that cannot be better than
// it (Errors::better_than) are not finished: their edge error alone already
// exceeds it (half of B0's trials are not taken). The figures' errors are
// left out: figure_errors() adds them to the errors of a step taken.
// `measured`: axis_areas() of `x` when known (empty otherwise).
Errors smooth_errors(const Deformation& d, const LeftOut& left_out, const std::vector<double>& log_lengths,
                     const Vertices& x, Slopes* slopes = nullptr, const Errors* beat = nullptr,
                     std::vector<double> measured = {}) {
  const QualityMeasure& q = d.quality;
  const auto& edges = q.edges();
  const auto& areas = q.input_areas();
  const Eigen::Index count = d.triangles().rows();
  std::vector<double> area = std::move(measured);
  double total = 0.0;
  if (area.empty())
    total = axis_areas(d, x, area);
  else
    for (double a : area) total += a;  // in axis_areas()'s order
  const double input_total = q.input_total_area();
  if (!(total > 0.0) || !(input_total > 0.0)) return {};
  const double s2 = total / input_total, log_scale = 0.5 * std::log(s2);
  const double edge_count = static_cast<double>(edges.size()), triangle_count = static_cast<double>(count);
  Errors errors{0.0, 0.0};
  // Each error's derivative by s^2, which moves with every triangle's area.
  std::array<double, 2> by_scale = {0.0, 0.0};
  if (slopes) slopes->edge.assign(edges.size(), std::numeric_limits<double>::quiet_NaN());
  for (size_t e = 0; e < edges.size(); ++e) {
    if (left_out.edges[e] || q.input_lengths()[e] <= 0.0) continue;
    const auto [i, j] = edges[e];
    const double length2 = (x.row(i) - x.row(j)).squaredNorm();
    if (!(length2 > 0.0)) return {};
    const double u = 0.5 * std::log(length2) - log_scale - log_lengths[e];
    const double rho_u = rho(u), slope = u / rho_u;  // rho(u) and its slope
    errors.edge += rho_u;
    by_scale[0] -= slope / (2.0 * s2 * edge_count);
    if (slopes) slopes->edge[e] = slope / (length2 * edge_count);
  }
  errors.edge /= edge_count;
  if (beat && errors.edge > beat->edge) return {};
  std::vector<double> by_area(count, 0.0);  // the area error's derivative by A at fixed s^2
  for (Eigen::Index t = 0; t < count; ++t) {
    if (left_out.triangles[t] || areas[t] <= 0.0) continue;
    if (!(area[t] > 0.0)) return {};
    const double r = std::log(area[t] / (s2 * areas[t]));
    const double rho_r = rho(r), slope = r / rho_r;  // rho(r) and its slope
    errors.area += rho_r;
    by_scale[1] -= slope / (s2 * triangle_count);
    by_area[t] = slope / (area[t] * triangle_count);
  }
  errors.area /= triangle_count;
  if (slopes) {
    slopes->by_area = std::move(by_area);
    slopes->by_scale = by_scale;
  }
  return errors;
}

// The figures' own edge and area errors (quality.h) at `x`, into `errors`.
void figure_errors(const Deformation& d, const Vertices& x, Errors& errors) {
  const QualityMeasure& q = d.quality;
  const auto& edges = q.edges();
  const auto& lengths = q.input_lengths();
  const auto& areas = q.input_areas();
  const Triangles& triangles = d.triangles();
  std::vector<double> area;
  double figure_total = 0.0;
  axis_areas(d, x, area, &figure_total);
  const double figure_s2 = figure_total / q.input_total_area(), figure_scale = std::sqrt(figure_s2);
  double figure_edge = 0.0, figure_area = 0.0;
  long measured_edges = 0, measured_triangles = 0;
  for (size_t e = 0; e < edges.size(); ++e) {
    if (lengths[e] <= 0.0) continue;
    const auto [i, j] = edges[e];
    figure_edge += std::abs((x.row(i) - x.row(j)).norm() / (figure_scale * lengths[e]) - 1.0);
    ++measured_edges;
  }
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    if (areas[t] <= 0.0) continue;
    figure_area += std::abs(std::abs(area[t]) / (figure_s2 * areas[t]) - 1.0);
    ++measured_triangles;
  }
  errors.figure_edge = measured_edges > 0 ? figure_edge / measured_edges : 0.0;
  errors.figure_area = measured_triangles > 0 ? figure_area / measured_triangles : 0.0;
}

// A step tried: the blend and its smooth errors (and what their gradients need).
struct Trial {
  Vertices next;
  Errors errors;
  Slopes slopes;
};

// Trials go in pairs (polish_stage) from this many triangles, below which
// one costs about what waking a thread for it does. A trial's own loops
// then run on its thread alone (run_tasks.h): at scale its errors, on one
// thread anyway, take a third of it.
constexpr Eigen::Index kPairedTrialsFrom = 5'000;

// Each smooth error's gradient by position at `x`, from the `slopes` of
// smooth_errors() at the same `x`.
void smooth_gradients(const Deformation& d, const Vertices& x, const Slopes& slopes,
                      std::array<Vertices, 2>& gradients) {
  const auto& edges = d.quality.edges();
  const double input_total = d.quality.input_total_area();
  const Triangles& triangles = d.triangles();
  for (Vertices& g : gradients) g.setZero(x.rows(), 3);
  for (size_t e = 0; e < edges.size(); ++e) {
    if (std::isnan(slopes.edge[e])) continue;
    const auto [i, j] = edges[e];
    const Eigen::RowVector3d v = x.row(i) - x.row(j);
    const Eigen::RowVector3d g = slopes.edge[e] * v;
    gradients[0].row(i) += g;
    gradients[0].row(j) -= g;
  }
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    // A's gradient: half the opposite edge turned about the axis.
    const Eigen::Vector3d axis = label_axis(d.triangle_labels[t]);
    const int a = triangles(t, 0), b = triangles(t, 1), c = triangles(t, 2);
    const Eigen::Vector3d pa = x.row(a), pb = x.row(b), pc = x.row(c);
    const std::array<double, 2> by = {slopes.by_scale[0] / input_total,
                                      slopes.by_area[t] + slopes.by_scale[1] / input_total};
    for (int k = 0; k < 2; ++k) {
      const double f = 0.5 * by[k];
      gradients[k].row(a) += f * (pb - pc).cross(axis).transpose();
      gradients[k].row(b) += f * (pc - pa).cross(axis).transpose();
      gradients[k].row(c) += f * (pa - pb).cross(axis).transpose();
    }
  }
}

// The figures' errors into `errors` and the smooth errors' gradients, both
// at `x` (of which `errors` and `slopes` are): independent, on a thread each.
void figures_and_gradients(const Deformation& d, const Vertices& x, Errors& errors, const Slopes& slopes,
                           std::array<Vertices, 2>& gradients) {
  run_tasks(2, [&](int i) {
    if (i == 0)
      figure_errors(d, x, errors);
    else
      smooth_gradients(d, x, slopes, gradients);
  });
}

// Vertices on an edge of one triangle: held where they are. An open
// boundary is where the user's mesh ends or continues, and the remesher
// lays it along grid lines (quad_remesh.h); moved by the polish, the
// shark's fourth hole turned back on itself and the remesh had 83
// irregular vertices instead of 43.
std::vector<char> open_boundary_vertices(int n, const Triangles& triangles) {
  std::vector<std::pair<int, int>> edges;
  edges.reserve(3 * static_cast<size_t>(triangles.rows()));
  for (Eigen::Index t = 0; t < triangles.rows(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles(t, k), b = triangles(t, (k + 1) % 3);
      edges.emplace_back(std::min(a, b), std::max(a, b));
    }
  sort_by_vertex(edges, n);
  std::vector<char> boundary(n, 0);
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j] == edges[i]) ++j;
    if (j - i == 1) boundary[edges[i].first] = boundary[edges[i].second] = 1;
    i = j;
  }
  return boundary;
}

// The slivers the run collapsed onto a line (flatten_charts.h) stay on it:
// their corners share a coordinate besides their chart's.
void keep_collapsed_on_their_lines(const RobustRun& run, ChartPlanes& planes) {
  const Deformation& d = run.d;
  const Triangles& triangles = d.triangles();
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    if (!run.state.collapsed[t]) continue;
    for (int axis = 0; axis < 3; ++axis) {
      if (axis == d.triangle_labels[t] / 2) continue;
      const double c = d.x(triangles(t, 0), axis);
      if (d.x(triangles(t, 1), axis) == c && d.x(triangles(t, 2), axis) == c) planes.collapse(t, axis);
    }
  }
}

// The bounds on every triangle's area (header): the run's largest ratio and
// half its smallest, or kPolishStretch either way; from the run's face
// states, whose areas, collapses and scale are fold_flags' (quality.h).
AreaBounds area_bounds(const Deformation& d, const FaceStates& state) {
  AreaBounds bounds;
  bounds.scale2 = state.scale2;
  bounds.smallest = 1.0 / kPolishStretch;
  bounds.largest = kPolishStretch;
  const std::vector<double>& input_areas = d.quality.input_areas();
  for (size_t t = 0; t < state.area.size(); ++t) {
    if (!(input_areas[t] > 0.0)) continue;
    const double ratio = state.area[t] / (bounds.scale2 * input_areas[t]);
    bounds.largest = std::max(bounds.largest, ratio);
    if (!state.collapsed[t]) bounds.smallest = std::min(bounds.smallest, 0.5 * ratio);
  }
  // A triangle collapses below kCollapsedAreaRatio at the current scale,
  // which a step moves: twice that keeps every triangle the run left open
  // open at any scale up to twice the run's.
  bounds.smallest = std::max(bounds.smallest, 2.0 * kCollapsedAreaRatio);
  return bounds;
}

// What the run left collapsed: its collapsed triangles and edges of no length.
LeftOut left_out_of(const RobustRun& run) {
  const Deformation& d = run.d;
  LeftOut left_out;
  left_out.triangles = run.state.collapsed;
  const auto& edges = d.quality.edges();
  left_out.edges.resize(edges.size());
  for (size_t e = 0; e < edges.size(); ++e)
    left_out.edges[e] = !((d.x.row(edges[e].first) - d.x.row(edges[e].second)).squaredNorm() > 0.0);
  return left_out;
}

// Each error's gradient smoothed by the flat charts' Laplacian L (a Sobolev
// gradient: a step along it keeps the charts flat and moves regions rather
// than single vertices; two back-substitutions), then the blend of the two
// shortest in L's norm: along it neither error grows (the common descent
// direction of two objectives) unless no step can do that. `beside` runs
// beside the back-substitutions (ChartPlanes::solve).
Vertices common_descent(const ChartPlanes& planes, const std::array<Vertices, 2>& gradients,
                        const std::function<void()>& beside) {
  const std::array<Vertices, 2> steps = planes.solve(-gradients[0], -gradients[1], beside);
  // <s_i, s_j> in L's norm is -g_i . s_j.
  const double a = -(gradients[0].cwiseProduct(steps[0])).sum(), b = -(gradients[1].cwiseProduct(steps[1])).sum(),
               c = -(gradients[0].cwiseProduct(steps[1])).sum();
  const double weight = a + b - 2.0 * c > 0.0 ? std::clamp((b - c) / (a + b - 2.0 * c), 0.0, 1.0) : 0.5;
  return weight * steps[0] + (1.0 - weight) * steps[1];
}

}  // namespace

int polish_stage(RobustRun& run, std::unique_ptr<ChartPlanes> factored) {
  Deformation& d = run.d;
  ChartPlanes planes(d.n, d.triangles(), d.triangle_labels);
  keep_collapsed_on_their_lines(run, planes);
  if (factored) {
    planes.share_factors(*factored);
    factored.reset();  // its other factors: not in memory beside new ones
  }
  planes.factorize(d.laplacian.matrix());
  // What the steps need, independent parts of it on a thread each.
  std::optional<BlendIndex> index;
  Figures start;
  AreaBounds bounds;
  LeftOut left_out;
  std::vector<double> log_lengths;
  std::vector<char> held;
  run_tasks(2, [&](int i) {
    if (i == 0) {
      index.emplace(d, planes);
      start = d.quality.measure(d.x, run.state);
      bounds = area_bounds(d, run.state);
      return;
    }
    left_out = left_out_of(run);
    log_lengths = log_lengths_of(d.quality);
    held = open_boundary_vertices(d.n, d.triangles());
  });
  const std::vector<char>& collapsed = run.state.collapsed;
  double step_length = 0.0;
  std::vector<double> sums;
  std::array<Vertices, 2> gradients;
  Slopes slopes;
  // The triangles' areas where the step starts: the run's, until a step moves them.
  std::vector<double> areas_now = run.state.area;
  std::vector<char> unused_collapsed, unused_flipped;
  // Steps follow the smooth errors; what is returned is the state, after
  // any step, with the lowest figures of those in which neither grew.
  Errors errors = smooth_errors(d, left_out, log_lengths, d.x, &slopes);
  // No smooth errors to lower (no area along the axes at all, or an edge the
  // run squeezed to nothing besides its collapsed ones): nothing to polish.
  if (!std::isfinite(errors.edge + errors.area)) return 0;
  figures_and_gradients(d, d.x, errors, slopes, gradients);
  Errors best = errors;
  slopes = Slopes();  // each trial has its own (Trial)
  const Vertices start_x = d.x;
  Vertices best_x = d.x;
  int steps = 0, best_steps = 0;
  const Eigen::Index count = d.triangles().rows();
  const bool paired_trials = count >= kPairedTrialsFrom && task_threads(2) > 1;
  for (; steps < kPolishRounds; ++steps) {
    // A step costs a second at a million triangles; a stop keeps the best so far.
    if (d.options.stop_requested && d.options.stop_requested()) break;
    const double sum = errors.edge + errors.area;
    sums.push_back(sum);
    if (steps >= kPolishWindow && sums[steps - kPolishWindow] - sum < kPolishGain * sum) break;
    // The areas where this step starts, measured beside the descent's
    // back-substitutions (the run's until a step moves them).
    const Vertices direction = common_descent(planes, gradients, [&] {
      if (steps > 0) d.quality.fold_flags(d.x, unused_collapsed, unused_flipped, &areas_now);
    });
    d.result.back_substitutions += 2;
    const double largest = direction.rowwise().norm().maxCoeff();
    if (!(largest > 0.0)) break;
    if (step_length == 0.0) step_length = kPolishFirstStep * run.diagonal / largest;
    const std::vector<char> rigid = rigid_axes(d, planes, direction);
    // The longest step, halving from twice the last one kept, along which
    // neither smooth error grows.
    auto trial = [&](double length) {
      Trial t;
      std::vector<double> measured;
      t.next = controlled_blend(d, planes, *index, rigid, d.x + length * direction, collapsed, bounds, held, areas_now,
                                &measured);
      t.errors = smooth_errors(d, left_out, log_lengths, t.next, &t.slopes, &errors, std::move(measured));
      return t;
    };
    // With a second core, a trial of the full length has the next halving's
    // tried beside it: the same trials in the same order, but one that fails
    // costs no time (every round of B0's polish failed at twice the last
    // step, then took the last step).
    std::array<Trial, 2> pair;
    bool moved = false, paired = false;
    for (int halving = 0; halving <= 2 * kMaxHalvings; ++halving) {
      if (paired) {
        paired = false;
        pair[0] = std::move(pair[1]);
      } else if (paired_trials && halving < 2 * kMaxHalvings) {
        paired = true;
        run_tasks(2, [&](int i) { pair[i] = trial(i == 0 ? step_length : 0.5 * step_length); });
      } else {
        pair[0] = trial(step_length);
      }
      Trial& t = pair[0];
      if (!t.errors.better_than(errors)) {
        step_length *= 0.5;
        continue;
      }
      figures_and_gradients(d, t.next, t.errors, t.slopes, gradients);
      // Placing moves each component as a whole: the errors and their gradients
      // stay.
      d.x = place_components(t.next, t.next, d.parts, d.centroids);
      errors = t.errors;
      moved = true;
      break;
    }
    if (!moved) break;
    step_length *= 2.0;
    if (errors.better_figures_than(best)) {
      best = errors;
      best_x = d.x;
      best_steps = steps + 1;
    }
  }
  d.result.factorizations += planes.factorizations();
  d.x = std::move(best_x);
  if (best_steps == 0) return 0;
  // Measured once more as the report does, before keeping it.
  FaceStates state = d.quality.face_states(d.x);
  const Figures figures = d.quality.measure(d.x, state);
  if (!(figures.edge_error <= start.edge_error && figures.area_error <= start.area_error)) {
    d.x = start_x;
    return 0;
  }
  run.state = std::move(state);
  d.result.figures = figures;
  return best_steps;
}

}  // namespace polycube
