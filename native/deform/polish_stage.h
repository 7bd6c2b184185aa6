// The robust variant's last touch on an exact polycube (docs/design.md
// section 2.6, "Polish"): the figures' edge and area errors lowered
// directly, the charts kept flat and nothing turned over or newly collapsed.
//
// Why: relaxing (relax_stage.h) minimises an as-rigid-as-possible energy,
// which is not the figures, and its whole-mesh blend stops at the first
// sliver in its way (fandisk, eight: every blend towards its target, even
// 1/64 of it, turns one over), leaving most of the mesh where it was. Here:
// - the energy is the two errors themselves made smooth (the logarithms of
//   the length and area ratios, their absolute values rounded off), with
//   the scale they are measured at a function of the positions;
// - a step follows both errors' gradients smoothed by the flat charts'
//   Laplacian, blended so that neither grows (the common descent direction
//   of two objectives), and is taken only when neither does; the state
//   returned is the one with the lowest figures of those in which neither
//   figure grew (the smooth errors are not quite the figures);
// - each step is controlled per unknown, not as a whole: a chart's plane,
//   and each coordinate a vertex has of its own, take their own share of
//   the step, halved where a triangle around them would turn over or leave
//   its area bounds. Unknowns shared by several vertices (a chart's plane,
//   a line a sliver was collapsed onto) move as one, so the charts stay
//   flat.
// The bounds: each triangle's area ratio (over its scaled input area) stays
// between half the run's smallest and its largest, widened to
// [1 / kPolishStretch, kPolishStretch]; the mean errors alone let a fin grow
// (the dragon's largest area ratio went from 28 to 53) and a sliver thin out
// until its shape key, in single precision, turned over (fandisk in
// Blender). Vertices on an open boundary stay where the run left them.
// It comes after every decision of the run (stage 8's further runs compare
// collapsed areas, not errors), so it changes none of them.
//
// Input: a RobustRun whose positions are an exact, fold-free polycube of its
// labels, its Laplacian assembled, and optionally `factored`: flat charts
// factorised with that Laplacian (those the run ended with), whose factors
// serve the axes on which the polish's charts are the same
// (ChartPlanes::share_factors); they are freed before any other is
// factorised. Output: the steps kept (0: the positions
// are unchanged, as when either figure would have grown); when more than 0,
// run.state and run.d.result.figures are those of the new positions.
#pragma once

#include <memory>

namespace polycube {

class ChartPlanes;
struct RobustRun;

// At most this many steps (most of the gain comes first: B0's edge error
// 0.031 -> 0.025 in ten, 23 more gain another 0.001), fewer once the last
// kPolishWindow steps together lowered the smooth errors' sum by less than
// kPolishGain of it.
constexpr int kPolishRounds = 10;
constexpr int kPolishWindow = 5;
constexpr double kPolishGain = 0.01;
// A step is taken only when it lowers the sum by at least this share of
// it; a length that gains less is halved like one that gains nothing, and
// when no length gains that much the polish ends: the descent has come to
// rest against the step control, and steps that small gain as little for
// the same cost (B0 refined 64 times: 2.6e-5 after 12 halvings, then 1e-7
// and 0, 1.3 s for the edge error's sixth decimal; the least a step of the
// CGAL models gains is 1.7e-4). Not taken, because a long step that the
// step control holds back almost everywhere gains next to nothing where a
// shorter one, held back less, still gains: fandisk refined 64 times took
// such a step second and ended there, edge and area error 0.105 / 0.139,
// where shorter steps reach 0.099 / 0.123 in ten.
constexpr double kPolishStall = 1e-4;
// Area ratios (Figures::max_area_ratio) up to this, and down to its inverse,
// are allowed wherever the run's own triangles span less (the eight's
// largest is 2.2): the bounds are against fins and slivers, not change.
constexpr double kPolishStretch = 4.0;
// The first step's largest move, a share of the bounding box diagonal.
constexpr double kPolishFirstStep = 0.005;

int polish_stage(RobustRun& run, std::unique_ptr<ChartPlanes> factored = nullptr);

}  // namespace polycube
