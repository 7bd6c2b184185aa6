#include "deform/untangle_flat_charts.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

#include "deform/barrier_energy.h"
#include "linear_algebra/minimize_lbfgs.h"
#include "linear_algebra/minimize_newton.h"
#include "linear_algebra/parallel.h"
#include "mesh/union_find.h"

namespace polycube {
namespace {

// Shape against area in the energy (header): equal parts keep both the edge
// and the area error down (fandisk: 0.113 / 0.179 before, 0.110 / 0.164).
constexpr double kTheta = 0.5;
// The first barrier width, in units of the determinant (1 = input area): wide
// enough to pull collapsed triangles open, narrow enough that shrinking the
// whole map does not pay (with eps = 1 it does).
constexpr double kFirstEps = 0.1;
// Each round lowers eps by at least this share (Garanzha et al.'s rule,
// with a larger floor: we need positive area, not the exact minimiser).
constexpr double kMinEpsDecrease = 0.3;
constexpr int kIterationsPerRound = 300;
// L-BFGS's iterations in a round that starts untangled (every triangle with
// room: the finishing round after local rounds, header). It starts near its minimum,
// and the iterations past these lower the edge error by about 1% at the
// cost of a round over the whole mesh (diplodocus: 1.4 s each, two or three
// per untangling, eight untanglings; deformation 42 -> 22 s, collapsed area
// 0.14% -> 0.12%, edge error 0.295 -> 0.307).
constexpr int kPolishIterations = 100;
// Newton's iterations per round: from the last round's minimum it needs a
// few; the cap only bounds a round that creeps.
constexpr int kNewtonIterations = 50;
// A Newton round stops once an iteration lowers the energy by less than this
// share: each round's minimum is only the start of the next, narrower one,
// and the last iterations before this creep (a tenth of a percent each) on
// triangles the barrier still holds inverted.
constexpr double kNewtonSettled = 1e-3;
// Triangles whose Hessians are computed together and handed to Newton's
// system (minimize_newton.h) at once: 4.7 MB, where the whole mesh's at
// once took 36 numbers per triangle beside the factor.
constexpr long kHessianBlock = 1L << 14;
// Room: a determinant (area over scaled input area) above this. Far below
// the collapsed threshold (quality.h), far above rounding: triangles that
// the charts hold on a line through a chain of shared unknowns come out
// near 1e-17, and at that level their sign is noise.
constexpr double kRoom = 1e-6;
// Done when every triangle has area and a round lowers the energy by less
// than this share.
constexpr double kSettled = 0.01;
// Triangles without room are put on a line only once the rounds stop
// freeing them: while a round leaves fewer than this share of the last
// round's, the barrier is still working (elephant: 4.4% of the area
// collapsed when put on a line after the second round, 2.7% with this).
constexpr double kStalled = 0.9;
// A local round (header) moves the unknowns this many rings of triangles
// around the triangles without room, through unknowns shared by at most
// this many vertices: not the chart planes, which the global rounds have
// placed already.
constexpr int kLocalRings = 3;
constexpr double kLocalMaxUses = 4;
// Rounds go local also with up to this many triangles without room, when
// they are at most kLocalCountShare of the triangles: a few dozen stuck
// triangles in a mesh of tens of thousands (turbine's bolt holes: 41 of
// 18,460) otherwise keep every round global, each one a minimisation over
// the whole mesh (turbine: untangling 6.8 -> 2.7 s, collapsed 0.51% ->
// 0.50% of the area; diplodocus 44 -> 37 s). Not on small meshes, where a
// share that large is a region whose charts the global rounds must still
// move (anchor, 2,100 triangles: 33% of its area collapsed with local
// rounds from 200).
constexpr double kLocalCount = 200;
constexpr double kLocalCountShare = 0.01;
// A local round of Newton's with this many triangles or more starts with a
// round of L-BFGS's: where the coarse route's polycube is carried to the
// fine mesh, tens of thousands of triangles are turned over, and Newton's
// first steps are cut to a half or an eighth by the line search, a
// factorisation each (bunny00 refined 16 times: 24 iterations, 6.5 s, in a
// round of 161,537 triangles), where L-BFGS's cost an energy each. Newton
// then finishes from its minimum (7 iterations; the round 3.8 s, the energy
// reached 0.214 against 0.228). Below, a factorisation costs little.
constexpr long kLbfgsFirstFrom = kUntangleNewtonFrom;

struct Triangle {
  std::array<std::array<int, 2>, 3> unknown;  // per corner: the unknowns of its two in-plane coordinates
  Eigen::Matrix2d inverse_reference;          // of the scaled input edges (columns)
  double weight = 0.0;                        // scaled input area
};

// The two in-plane axes of a label, ordered so that a positive determinant
// means the normal points along the label's axis.
std::array<int, 2> plane_axes(int label) {
  const int axis = label / 2, b = (axis + 1) % 3, c = (axis + 2) % 3;
  return label % 2 == 0 ? std::array<int, 2>{b, c} : std::array<int, 2>{c, b};
}

bool on_a_line(const Triangle& t) {
  for (int c = 0; c < 2; ++c)
    if (t.unknown[0][c] == t.unknown[1][c] && t.unknown[1][c] == t.unknown[2][c]) return true;
  for (int i = 0; i < 3; ++i)
    if (t.unknown[i] == t.unknown[(i + 1) % 3]) return true;
  return false;
}

// Always inlined: the minimisations call it for every triangle, every gradient.
[[gnu::always_inline]] inline double determinant(const Triangle& t, const Eigen::VectorXd& y,
                                                 Eigen::Matrix2d* jacobian = nullptr) {
  Eigen::Matrix2d edges;
  for (int e = 0; e < 2; ++e)
    for (int c = 0; c < 2; ++c) edges(c, e) = y[t.unknown[e + 1][c]] - y[t.unknown[0][c]];
  const Eigen::Matrix2d j = edges * t.inverse_reference;
  if (jacobian) *jacobian = j;
  return j.determinant();
}

using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The energy's lanes (barrier_energy_lanes): triangles side by side.
constexpr int kLanes = 8;

// Triangle t's Jacobian at `y` into lane i of `j` (entry J(c, k) at
// j[c + 2 k]), the same products and sums as determinant()'s.
[[gnu::always_inline]] inline void jacobian_lane(const Triangle& t, const Eigen::VectorXd& y, double (&j)[4][kLanes],
                                                 int i) {
  const Eigen::Matrix2d& r = t.inverse_reference;
  for (int c = 0; c < 2; ++c) {
    const double edge0 = y[t.unknown[1][c]] - y[t.unknown[0][c]], edge1 = y[t.unknown[2][c]] - y[t.unknown[0][c]];
    j[c][i] = edge0 * r(0, 0) + edge1 * r(1, 0);
    j[c + 2][i] = edge0 * r(0, 1) + edge1 * r(1, 1);
  }
}

// The energy of `count` triangles from `list` at `at`, summed in their
// order, and when `gradient` is not null each one's gradient added to it
// there (corner 0 gets minus the other two's). (Built for AVX2 as well, it
// was no faster: the gathers and the scatter then take the time.)
double energy_of_range(const Triangle* list, long count, const Eigen::VectorXd& at, double eps, double* gradient) {
  double total = 0.0;
  for (long first = 0; first < count; first += kLanes) {
    const int lanes = static_cast<int>(std::min<long>(kLanes, count - first));
    double j[4][kLanes], weight[kLanes], value[kLanes], by_j[4][kLanes];
    for (int i = 0; i < kLanes; ++i) {
      // Lanes past the end repeat the last triangle (finite, not summed).
      const Triangle& t = list[first + std::min(i, lanes - 1)];
      jacobian_lane(t, at, j, i);
      weight[i] = t.weight;
    }
    barrier_energy_lanes(j, weight, eps, kTheta, value, gradient ? by_j : nullptr);
    for (int i = 0; i < lanes; ++i) {
      total += value[i];
      if (!gradient) continue;
      const Triangle& t = list[first + i];
      const Eigen::Matrix2d& r = t.inverse_reference;
      for (int c = 0; c < 2; ++c) {
        // The gradient by the two edges: by J times the reference's inverse transposed.
        const double by_edge0 = by_j[c][i] * r(0, 0) + by_j[c + 2][i] * r(0, 1);
        const double by_edge1 = by_j[c][i] * r(1, 0) + by_j[c + 2][i] * r(1, 1);
        gradient[t.unknown[1][c]] += by_edge0;
        gradient[t.unknown[2][c]] += by_edge1;
        gradient[t.unknown[0][c]] -= by_edge0 + by_edge1;
      }
    }
  }
  return total;
}

// Its Hessian, positive semi-definite, in its six corner coordinates (corner
// j's in-plane coordinate c at 2 j + c): barrier_hessian() in J, carried
// through J's linear map in the corners, which keeps it so.
Matrix6d triangle_hessian(const Triangle& t, const Eigen::VectorXd& at, double eps) {
  Eigen::Matrix2d j;
  determinant(t, at, &j);
  // J(c, k) = sum over corners of corner[c] * spread(corner, k).
  Eigen::Matrix<double, 3, 2> spread;
  spread.row(1) = t.inverse_reference.row(0);
  spread.row(2) = t.inverse_reference.row(1);
  spread.row(0) = -spread.row(1) - spread.row(2);
  Eigen::Matrix<double, 4, 6> map = Eigen::Matrix<double, 4, 6>::Zero();
  for (int corner = 0; corner < 3; ++corner)
    for (int c = 0; c < 2; ++c)
      for (int k = 0; k < 2; ++k) map(c + 2 * k, 2 * corner + c) = spread(corner, k);
  return map.transpose() * barrier_hessian(j, t.weight, eps, kTheta) * map;
}

}  // namespace

UntangledCharts untangle_flat_charts(const Vertices& input, const Vertices& flat, const Triangles& triangles,
                                     const std::vector<int>& triangle_labels, int max_rounds, double local_share,
                                     const CollapseBound& bound, UntangleMinimiser minimiser,
                                     const std::function<bool()>& stop,
                                     const std::function<void()>& before_global, UntangleStart start) {
  const bool local_only = start != UntangleStart::as_needed;
  const int n = static_cast<int>(input.rows());
  const Eigen::Index count = triangles.rows();
  UntangledCharts result;
  result.positions = flat;

  // The input's shapes, scaled to the polycube's total area.
  double area_in = 0.0, area_flat = 0.0;
  for (Eigen::Index t = 0; t < count; ++t) {
    const Eigen::Vector3d a = input.row(triangles(t, 0)), b = input.row(triangles(t, 1)),
                          c = input.row(triangles(t, 2));
    const Eigen::Vector3d p = flat.row(triangles(t, 0)), q = flat.row(triangles(t, 1)), r = flat.row(triangles(t, 2));
    area_in += 0.5 * (b - a).cross(c - a).norm();
    area_flat += 0.5 * (q - p).cross(r - p).norm();
  }
  // Lengths in units of sqrt(area_flat): the polycube has area 1, and the
  // minimisation's tolerances mean the same at every scale.
  if (!(area_in > 0.0) || !(area_flat > 0.0)) return result;
  const double unit = std::sqrt(area_flat), scale = 1.0 / std::sqrt(area_in);

  // Unknowns: per axis, one per chart plane (vertices joined by triangles of
  // that axis) and one per vertex off every plane of that axis.
  Eigen::MatrixX3i unknown_of(n, 3);
  std::vector<double> value;
  for (int axis = 0; axis < 3; ++axis) {
    UnionFind planes(n);
    std::vector<char> on_plane(n, 0);
    for (Eigen::Index t = 0; t < count; ++t) {
      if (triangle_labels[t] / 2 != axis) continue;
      for (int j = 0; j < 3; ++j) on_plane[triangles(t, j)] = 1;
      planes.join(triangles(t, 0), triangles(t, 1));
      planes.join(triangles(t, 0), triangles(t, 2));
    }
    std::vector<int> plane_unknown(n, -1);
    for (int v = 0; v < n; ++v) {
      if (!on_plane[v]) {
        unknown_of(v, axis) = static_cast<int>(value.size());
        value.push_back(flat(v, axis) / unit);
        continue;
      }
      int& u = plane_unknown[planes.root(v)];
      if (u < 0) {
        u = static_cast<int>(value.size());
        value.push_back(0.0);
      }
      unknown_of(v, axis) = u;
    }
    // A plane's value: its vertices' mean (they agree up to rounding).
    std::vector<int> size(value.size(), 0);
    for (int v = 0; v < n; ++v)
      if (on_plane[v]) {
        const int u = unknown_of(v, axis);
        value[u] = (size[u] * value[u] + flat(v, axis) / unit) / (size[u] + 1);
        ++size[u];
      }
  }
  const int unknowns = static_cast<int>(value.size());
  std::vector<double> uses(unknowns, 0.0);
  for (int v = 0; v < n; ++v)
    for (int axis = 0; axis < 3; ++axis) uses[unknown_of(v, axis)] += 1.0;

  std::vector<Triangle> all;
  all.reserve(count);
  for (Eigen::Index t = 0; t < count; ++t) {
    const Eigen::Vector3d a = input.row(triangles(t, 0));
    const Eigen::Vector3d e1 = Eigen::Vector3d(input.row(triangles(t, 1))) - a;
    const Eigen::Vector3d e2 = Eigen::Vector3d(input.row(triangles(t, 2))) - a;
    const Eigen::Vector3d normal = e1.cross(e2);
    const double length = e1.norm(), doubled_area = normal.norm();
    Triangle triangle;
    if (!(length > 0.0) || !(doubled_area > 0.0)) {
      triangle.weight = 0.0;  // no shape to keep: left out
    } else {
      const Eigen::Vector3d u = e1 / length, w = normal.cross(u) / doubled_area;
      Eigen::Matrix2d reference;
      reference << length, e2.dot(u), 0.0, e2.dot(w);
      triangle.inverse_reference = (scale * reference).inverse();
      triangle.weight = 0.5 * doubled_area * scale * scale;
    }
    const std::array<int, 2> axes = plane_axes(triangle_labels[t]);
    for (int j = 0; j < 3; ++j)
      for (int c = 0; c < 2; ++c) triangle.unknown[j][c] = unknown_of(triangles(t, j), axes[c]);
    all.push_back(triangle);
  }

  // Unknowns joined to put triangles without room on a line.
  UnionFind joined(unknowns);
  Eigen::VectorXd x = Eigen::Map<const Eigen::VectorXd>(value.data(), unknowns);
  std::vector<Triangle> active;     // in slots, those with room
  std::vector<int> source;          // active -> all
  std::vector<int> slot(unknowns);  // unknown -> entry of the minimised vector
  Eigen::VectorXd y;
  Eigen::VectorXd slot_users;  // vertices using each slot
  // Triangles of positive input area on a line (collapsed whatever follows)
  // and their share of the input's area (the weights sum to 1).
  int lined = 0;
  double lined_area = 0.0;
  auto rebuild = [&]() {
    std::vector<int> root_slot(unknowns, -1);
    int slots = 0;
    for (int u = 0; u < unknowns; ++u) {
      int& s = root_slot[joined.root(u)];
      if (s < 0) s = slots++;
      slot[u] = s;
    }
    // A joined unknown's value: its members' mean, weighted by the
    // vertices that use them, so a plane hardly moves for one vertex.
    Eigen::VectorXd sum = Eigen::VectorXd::Zero(slots), users = Eigen::VectorXd::Zero(slots);
    for (int u = 0; u < unknowns; ++u) sum[slot[u]] += uses[u] * x[u], users[slot[u]] += uses[u];
    y = sum.cwiseQuotient(users.cwiseMax(1.0));
    slot_users = users;
    active.clear();
    source.clear();
    // Grown in place, a million triangles' copy was moved a dozen times
    // (bunny00 refined 16 times: 0.8 of the 1.3 s before the first round).
    active.reserve(all.size());
    source.reserve(all.size());
    lined = 0;
    lined_area = 0.0;
    for (size_t i = 0; i < all.size(); ++i) {
      if (!(all[i].weight > 0.0)) continue;
      Triangle mapped = all[i];
      for (auto& corner : mapped.unknown)
        for (int& u : corner) u = slot[u];
      if (on_a_line(mapped)) {
        ++lined;
        lined_area += all[i].weight;
        continue;
      }
      active.push_back(mapped);
      source.push_back(static_cast<int>(i));
    }
  };
  // Past the caller's bound: rounding between this sum and the caller's own
  // measure of the same areas is far below the margin.
  auto past_bound = [&]() { return lined > bound.triangles || lined_area > bound.area + 1e-9; };
  rebuild();
  result.refused = past_bound();
  if (result.refused) return result;

  double eps = kFirstEps;
  // Per thread: its triangles' share of the gradient, summed afterwards.
  std::vector<Eigen::VectorXd> partial(std::max(1, parallel_threads(static_cast<long>(count))));
  auto energy_of = [&](const std::vector<Triangle>& list, const Eigen::VectorXd& at, Eigen::VectorXd* gradient,
                       const HessianSink* hessians) {
    const long size = static_cast<long>(list.size());
    const int threads = parallel_threads(size);
    double total = 0.0;
#pragma omp parallel for num_threads(threads) reduction(+ : total) schedule(static)
    for (int chunk = 0; chunk < threads; ++chunk) {
      Eigen::VectorXd& part = partial[chunk];
      if (gradient) part.setZero(at.size());
      const long first = size * chunk / threads, end = size * (chunk + 1) / threads;
      total += energy_of_range(list.data() + first, end - first, at, eps, gradient ? part.data() : nullptr);
    }
    if (hessians) {
      // In blocks, each computed on every thread, then handed over.
      std::vector<double> block(36 * std::min(size, kHessianBlock));
      for (long first = 0; first < size; first += kHessianBlock) {
        const long in_block = std::min(kHessianBlock, size - first);
#pragma omp parallel for num_threads(threads) schedule(static)
        for (long i = 0; i < in_block; ++i) {
          const Matrix6d hessian = triangle_hessian(list[first + i], at, eps);
          std::copy(hessian.data(), hessian.data() + 36, block.data() + 36 * i);
        }
        (*hessians)(first, in_block, block.data());
      }
    }
    if (gradient) {
      *gradient = partial[0];
      for (int chunk = 1; chunk < threads; ++chunk) *gradient += partial[chunk];
    }
    return total;
  };
  const bool newton_rounds =
      minimiser == UntangleMinimiser::newton ||
      (minimiser == UntangleMinimiser::automatic && static_cast<long>(active.size()) >= kUntangleNewtonFrom);
  // Minimises the energy of `list` over the first `free_count` entries of
  // `at` (the others held), by Newton's rounds or, with `by_lbfgs` or
  // without them, L-BFGS's; returns the energy reached.
  NewtonMinimizer global_newton;
  auto minimize_over = [&](const std::vector<Triangle>& list, Eigen::VectorXd& at, int free_count,
                           NewtonMinimizer& newton, bool by_lbfgs = false) {
    if (!newton_rounds || by_lbfgs) {
      const Objective objective = [&](const Eigen::VectorXd& p, Eigen::VectorXd& gradient) {
        const double value = energy_of(list, p, &gradient, nullptr);
        gradient.tail(gradient.size() - free_count).setZero();  // held
        return value;
      };
      const LbfgsResult run = minimize_lbfgs(objective, at, result.untangled ? kPolishIterations : kIterationsPerRound,
                                             1e-9, 1e-8, kLbfgsMemory, stop);
      result.stopped = result.stopped || run.stopped;
      result.iterations += run.iterations;
      return run.value;
    }
    std::vector<int> corners(6 * list.size());
    for (size_t i = 0; i < list.size(); ++i)
      for (int corner = 0; corner < 3; ++corner)
        for (int c = 0; c < 2; ++c) corners[6 * i + 2 * corner + c] = list[i].unknown[corner][c];
    const ElementObjective objective = [&](const Eigen::VectorXd& p, Eigen::VectorXd* gradient,
                                           const HessianSink* hessians) {
      return energy_of(list, p, gradient, hessians);
    };
    const NewtonResult run =
        newton.minimize(objective, corners, 6, free_count, at, kNewtonIterations, 1e-9, kNewtonSettled, stop);
    result.stopped = result.stopped || run.stopped;
    result.iterations += run.iterations;
    result.factorizations += run.factorizations;
    return run.value;
  };

  // A local round: only the unknowns within a few rings of the triangles
  // left without room move, the rest (and every plane shared by more than
  // a few vertices) held; only the triangles they touch are evaluated.
  std::vector<int> seeds;  // original unknowns of the last round's triangles without room
  auto minimize_locally = [&]() {
    const int slots = static_cast<int>(y.size());
    std::vector<char> free(slots, 0);
    auto movable = [&](int s) { return slot_users[s] <= kLocalMaxUses; };
    for (const int u : seeds)
      if (movable(slot[u])) free[slot[u]] = 1;
    for (int ring = 0; ring < kLocalRings; ++ring) {
      std::vector<char> grown = free;
      for (const Triangle& t : active) {
        bool touches = false;
        for (const auto& corner : t.unknown)
          for (const int s : corner) touches = touches || free[s];
        if (!touches) continue;
        for (const auto& corner : t.unknown)
          for (const int s : corner)
            if (movable(s)) grown[s] = 1;
      }
      free.swap(grown);
    }
    std::vector<int> local_of(slots, -1), order;
    for (int s = 0; s < slots; ++s)
      if (free[s]) local_of[s] = static_cast<int>(order.size()), order.push_back(s);
    const int free_count = static_cast<int>(order.size());
    std::vector<Triangle> local;
    for (const Triangle& t : active) {
      bool touches = false;
      for (const auto& corner : t.unknown)
        for (const int s : corner) touches = touches || free[s];
      if (!touches) continue;
      Triangle mapped = t;
      for (auto& corner : mapped.unknown)
        for (int& s : corner) {
          if (local_of[s] < 0) local_of[s] = static_cast<int>(order.size()), order.push_back(s);
          s = local_of[s];
        }
      local.push_back(mapped);
    }
    Eigen::VectorXd z(order.size());
    for (size_t i = 0; i < order.size(); ++i) z[i] = y[order[i]];
    NewtonMinimizer newton;
    if (newton_rounds && static_cast<long>(local.size()) >= kLbfgsFirstFrom)
      minimize_over(local, z, free_count, newton, true);
    if (!result.stopped) minimize_over(local, z, free_count, newton);
    for (int i = 0; i < free_count; ++i) y[order[i]] = z[i];
  };

  // Few enough triangles without room for a local round (header).
  auto few = [&](size_t without_room) {
    const double triangles_now = static_cast<double>(active.size());
    return local_share > 0.0 && without_room <= std::max(local_share * triangles_now,
                                                         std::min(kLocalCount, kLocalCountShare * triangles_now));
  };
  // The triangles without room at `at`; `smallest`: the least determinant.
  auto without_room = [&](const Eigen::VectorXd& at, double& smallest) {
    smallest = std::numeric_limits<double>::infinity();
    std::vector<int> no_room;
    for (size_t a = 0; a < active.size(); ++a) {
      const double d = determinant(active[a], at);
      smallest = std::min(smallest, d);
      if (!(d > kRoom)) no_room.push_back(static_cast<int>(a));
    }
    return no_room;
  };
  auto seed_with = [&](const std::vector<int>& no_room) {
    for (const int a : no_room)
      for (const auto& corner : all[source[a]].unknown)
        for (const int u : corner) seeds.push_back(u);
  };
  // With Newton's rounds (at scale), a map that turns no triangle over (a
  // relaxed polycube whose charts left slivers collapsed) is untangled by
  // local rounds alone, however many triangles lack room, and ends once
  // they have it: away from them it stays the caller's map, its planes
  // placed already. A global round there costs several factorisations of
  // the whole mesh (B0 refined 16 and 64 times: 80 and 203 slivers opened
  // in 0.15 and 1.5 s instead of 7 and 43 s, edge and area error lower
  // after the polish; bunny00 refined 4 times, 26,464 collapsed: 63 s of
  // global rounds, most of them one that crept for 50 Newton iterations,
  // against 8 s; docs/design.md section 2.6, stage 7, has what it does to
  // whole runs). Where triangles are turned over (a first flattening), the
  // global rounds still follow: fandisk's first flattening untangled with
  // local rounds alone had area error 0.188 instead of 0.172; and L-BFGS's
  // finishing round costs little and lowers the area error where it runs
  // (fandisk's relaxed slivers: 0.132, 0.153 without it).
  bool only_local = false;
  if (newton_rounds) {
    double smallest = 0.0;
    const std::vector<int> no_room = without_room(y, smallest);
    if ((local_only || !(smallest < -kRoom)) && !no_room.empty()) {
      seed_with(no_room);
      only_local = true;
    }
    if (local_only && no_room.empty()) {
      result.untangled = true;
      return result;
    }
  }
  double previous = std::numeric_limits<double>::infinity();
  size_t last_no_room = 0;
  bool global_started = false, finishing = false;
  // The caller's stop ends the rounds, the result refused (header).
  auto stopped = [&]() {
    result.stopped = result.stopped || (stop && stop());
    if (result.stopped) result.refused = true, result.untangled = false;
    return result.stopped;
  };
  for (result.rounds = 1; result.rounds <= max_rounds; ++result.rounds) {
    if (stopped()) break;
    double reached = 0.0;
    const bool local = !seeds.empty();
    only_local = only_local && local;
    if (!local) {
      if (before_global && !global_started) before_global();
      global_started = true;
      reached = minimize_over(active, y, static_cast<int>(y.size()), global_newton);
    } else {
      ++result.local_rounds;
      minimize_locally();
      reached = energy_of(active, y, nullptr, nullptr);
    }
    if (stopped()) break;
    double smallest = 0.0;
    const std::vector<int> no_room = without_room(y, smallest);
    for (int u = 0; u < unknowns; ++u) x[u] = y[slot[u]];
    const double decrease =
        std::isfinite(previous) ? std::max(1.0 - reached / previous, kMinEpsDecrease) : kMinEpsDecrease;
    const double previous_value = previous;
    const size_t previous_no_room = last_no_room;
    last_no_room = no_room.size();
    seeds.clear();
    if (only_local || few(no_room.size())) seed_with(no_room);
    previous = reached;
    result.untangled = no_room.empty();
    // `local_then_global`: one global round to finish, as the map may have
    // moved far from the caller's around the triangles opened (a polycube of
    // other labels). Fandisk refined 64 times, stage 8's further runs: edge
    // and area error 0.1055 / 0.1478 without it, 0.1049 / 0.1421 with it.
    if (finishing && !local) break;
    if (no_room.empty() && only_local) {
      if (start != UntangleStart::local_then_global) break;
      only_local = false;
      finishing = true;
    }
    if (no_room.empty()) {
      // The last round is global: the map away from the triangles that
      // were without room is minimised as before.
      if (!local && (eps < 1e-4 || 1.0 - reached / previous_value < kSettled)) break;
    } else if (result.rounds > 1 && no_room.size() > kStalled * previous_no_room) {
      // Stalled without area: no room in the charts.
      // Its corners share the coordinate in which it is thinnest (or that
      // two of them share already), which puts it on a line.
      for (const int a : no_room) {
        const Triangle& t = active[a];
        std::array<double, 2> extent{};
        for (int k = 0; k < 2; ++k) {
          const auto [lo, hi] = std::minmax({y[t.unknown[0][k]], y[t.unknown[1][k]], y[t.unknown[2][k]]});
          extent[k] = hi - lo;
        }
        const int c = extent[0] <= extent[1] ? 0 : 1;
        const Triangle& original = all[source[a]];
        joined.join(original.unknown[0][c], original.unknown[1][c]);
        joined.join(original.unknown[0][c], original.unknown[2][c]);
      }
      result.put_on_a_line += static_cast<int>(no_room.size());
      rebuild();
      if (past_bound()) {
        result.refused = true;
        result.untangled = false;
        break;
      }
    }
    // Garanzha et al.'s update: the barrier closes in on the smallest determinant.
    const double mu = (1.0 - decrease) * 0.5 * (smallest + std::sqrt(eps * eps + smallest * smallest));
    eps = smallest < mu ? 2.0 * std::sqrt(mu * (mu - smallest)) : 1e-12;
  }
  for (int v = 0; v < n; ++v)
    for (int axis = 0; axis < 3; ++axis) result.positions(v, axis) = unit * x[unknown_of(v, axis)];
  return result;
}

}  // namespace polycube
