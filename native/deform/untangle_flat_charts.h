// The last stage of the `robust` variant (docs/design.md section 2.6): an
// exact polycube whose collapsed triangles get their area back, without
// leaving their charts.
//
// Why: flatten_charts.h reaches the exact polycube by linear solves, which
// know nothing of orientation, and collapses every triangle that would turn
// over; what is collapsed is a hole in the polycube map (nothing downstream,
// UVs, quad remeshing, can use it): 0.8% of fandisk's area, 2-11% on organic
// models. Most of those triangles have room in their charts.
//
// How: every vertex keeps, per axis, either its chart's plane (shared with
// the chart's other vertices; the plane itself may move) or a coordinate of
// its own, so every placement of these unknowns is an exact polycube on the
// same charts. Over them we minimise each triangle's distortion from its
// scaled input shape, measured in its chart's plane, with the regularised
// barrier of Garanzha et al. 2021 ("Foldover-free maps in 50 lines of code"):
// with chi(d) = (d + sqrt(eps^2 + d^2)) / 2 of the Jacobian's determinant d,
// E = sum area_in ((1 - theta) |J|^2 / chi + theta (d^2 + 1) / chi),
// minimised again as eps shrinks, which takes triangles of zero or negative
// area to positive area where the charts allow it. A triangle still
// collapsed or turned over after a round has no room (the charts meet so
// that no placement gives it area): it is put on a line, its corners
// sharing one more unknown, and left out.
//
// Speed: once few triangles are without room (on organic models a handful
// out of tens of thousands, for round after round while eps shrinks), a
// round minimises only over their neighbourhoods, every other unknown and
// every chart plane held, and evaluates only the triangles there; the
// last round, with every triangle given room, is global again. Lion: the
// stage 3 times faster, 107 triangles collapsed instead of 119. At scale
// (Newton's rounds), a map that turns nothing over is untangled by local
// rounds alone, however many of its triangles are without room: the rest
// of it is returned as given.
#pragma once

#include <functional>
#include <limits>
#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct UntangledCharts {
  Vertices positions;      // every chart flat on its axis, like `flat`
  int rounds = 0;          // minimisations done (one per eps)
  int local_rounds = 0;    // of them, over the neighbourhoods of triangles without room
  int put_on_a_line = 0;   // triangles left collapsed: no room in their charts
  int iterations = 0;      // the minimiser's, over every round
  int factorizations = 0;  // Newton's sparse factorisations, over every round
  bool untangled = false;  // every other triangle has positive area in its chart
  bool refused = false;    // stopped once past the bound (below), or stopped: `positions` unfinished
  bool stopped = false;    // `stop` (below) answered true
};

// A triangle put on a line stays collapsed in every later round, so the
// triangles on a line are a lower bound on what any result collapses. A
// caller that refuses results collapsing more than a bound says so, and the
// rounds stop as soon as that bound is passed: at scale a round costs tens
// of seconds (armadillo refined 16 times: a refused attempt 907 s, 30
// rounds, and 116 s, 2 rounds, once stopped at 12% of the area on a line).
struct CollapseBound {
  double area = std::numeric_limits<double>::infinity();  // share of the input's area on a line
  int triangles = std::numeric_limits<int>::max();        // triangles (of positive input area) on a line
};

// How each round minimises: projected Newton (linear_algebra/minimize_newton.h)
// or L-BFGS (linear_algebra/minimize_lbfgs.h); automatic: Newton from 100,000
// triangles on, L-BFGS below. Newton's rounds reach a lower energy in a few
// factorisations where L-BFGS stops at its 300 gradients, which at scale
// costs less: the stage 62 -> 41 s on B0 refined 64 times, 84 -> 49 s on
// fandisk refined 16 times, edge error lower (peak memory 1.6 -> 3.0 GiB on
// B0: the factor). Below, a factorisation costs dozens of L-BFGS iterations,
// the untangling ends no faster (lion 4 -> 8 s), and the rounds, settled at
// each eps, leave more triangles without room to put on a line (fandisk 0 ->
// 21 collapsed, armadillo 182 -> 1348); L-BFGS's results there are kept bit
// for bit.
enum class UntangleMinimiser { automatic, newton, lbfgs };

// Where Newton's rounds start (at scale; below it every round is L-BFGS's
// and `as_needed`): global until few triangles lack room (`as_needed`); or
// local from the start, turned-over triangles included, as for a map that
// turns nothing over (above), for a map that is an untangled polycube but
// for a few faces: then one global round to finish once every triangle has
// room (`local_then_global`: stage 8's further runs from the result, whose
// map may have moved far around the faces relabelled), or none
// (`local_only`: a coarse polycube carried back, coarse_to_fine.h, whose map
// away from the triangles opened is the coarse run's minimum already; the
// global round, at a million triangles, was most of B0 refined 64 times'
// untangling, 22 of 25 s). Either local start returns `flat` as it is when
// every triangle has room from the start.
enum class UntangleStart { as_needed, local_then_global, local_only };

// From this many triangles on, `automatic` rounds are Newton's (above).
constexpr long kUntangleNewtonFrom = 100'000;
constexpr int kUntangleRounds = 30;
constexpr double kUntangleLocalShare = 0.002;

// `flat`: an exact polycube of `input` (every triangle on a plane of its
// label's axis, per-triangle labels 0..5), e.g. from flatten_charts.h.
// `local_share`: rounds are local once at most this share of the triangles
// is without room, or at most a couple of hundred that are a small share
// (0: never). `bound`: stop, refused, once the triangles on
// a line pass it. `stop`, when given, is asked before every round and every
// Newton iteration: true stops, refused (the user's stop, answered within a
// factorisation, where a round costs minutes at a million triangles).
// `before_global`, when given, is called once before the first global round
// (the caller's factors freed for Newton's, say: local rounds need little).
// `start`: where Newton's rounds start (above).
UntangledCharts untangle_flat_charts(const Vertices& input, const Vertices& flat, const Triangles& triangles,
                                     const std::vector<int>& triangle_labels, int max_rounds = kUntangleRounds,
                                     double local_share = kUntangleLocalShare, const CollapseBound& bound = {},
                                     UntangleMinimiser minimiser = UntangleMinimiser::automatic,
                                     const std::function<bool()>& stop = {},
                                     const std::function<void()>& before_global = {},
                                     UntangleStart start = UntangleStart::as_needed);

}  // namespace polycube
