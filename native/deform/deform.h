// The polycube deformation of docs/design.md section 2: iterate "rotate every
// triangle's normal onto its label axis, then solve L x = b" until the largest
// normal deviation is below the tolerance or the iteration limit is reached.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "deform/quality.h"
#include "mesh/mesh.h"

namespace polycube {

// Which Laplacian the Poisson solve uses. Every fixed point is an exact polycube
// whatever the weights, so both reach the same shapes; they differ in cost and
// robustness.
//
// `robust` (the default) is ours, not the paper's (docs/design.md sections 2.5-2.6). Why the plain
// method folds and stalls on real models, measured (200 iterations):
// - its step jumps: `fixed` turns faces over on its way even where it ends
//   exact (B0: 4 faces at iteration 4; fandisk: 43, 9 stay; elephant: 428);
//   `current` diverges once triangles degenerate (sphere: from iteration 40,
//   max 150 degrees; elephant: mean 47 degrees);
// - negative cotangents make L indefinite (16% of bone's corners are obtuse,
//   7% of fandisk's, 0% of the sphere's);
// - labels that ask for the impossible: faces pointing more than 90 degrees
//   away from their axis at the start (12 in bone's published labeling),
//   staircase chart boundaries that need faces collapsed, one-face charts
//   (136 in the elephant's nearest-axis labels), and quads bent across a
//   polycube edge, whose two triangles cannot share one label.
// What `robust` does, every part kept because the figures justified it:
// 1. positive weights (cotangents clamped at 0) for a semidefinite L;
// 2. a fitting phase: per-triangle rotations that turn the *input* normal onto
//    the axis with the best in-plane twist (fitted_rotations.h), global step
//    with the input Laplacian factorised once: an as-rigid-as-possible shape
//    close to the polycube, which cuts edge and area error;
// 3. then the exact polycube in one go (flatten_charts.h): every chart flat
//    on its plane by a constrained solve, the few slivers that would turn
//    over collapsed instead, then relaxed as rigidly as possible inside the
//    flat charts. Every face then has its axis' normal exactly: fandisk,
//    eight, bone, mesh_with_border, cactus, double-torus-example converge in
//    6 to 60 iterations instead of stalling 3 to 47 degrees off after 200;
//    the price is more collapsed slivers than `fixed` (fandisk 165 against
//    61, 1% of the area);
// 4. where the labels ask for more than slivers (flattening would collapse
//    over an eighth of the surface: elephant, anchor, armadillo, bunny00 with
//    nearest-axis labels), the continuous iteration goes on: the paper's step
//    with the input Laplacian, or, where that would fold a face, with the
//    current mesh's Laplacian, which collapses faces without turning them
//    (solved by conjugate gradients preconditioned by the input's
//    factorisation: no factorisation per iteration);
// 5. every step fold-free (fold_free_step.h): faces never turn over;
// 6. when progress stalls, faces held back near 90 degrees that fit a
//    neighbour's label better are relabelled (relabel_stalled_faces.h, listed in
//    DeformResult::relabelled_faces), and flattening is tried again.
// What is left (see tests/native/test_robust_deform.cpp): labels that cannot
// be met without crushing the model (elephant 90 degrees, anchor 90) need a
// better labelling, not a better deformation; the faces above the tolerance
// are listed in DeformResult::unconverged_faces.
enum class Variant {
  kFixed,    // built from the input once, factorised once: one back-substitution per iteration
  kCurrent,  // rebuilt from the current mesh every iteration, as in the paper
  kRobust,   // fold-free: input-shape fitting, then flat charts (or the paper's step under a step control)
};

constexpr Variant kVariants[] = {Variant::kRobust, Variant::kFixed, Variant::kCurrent};
Variant parse_variant(const std::string& name);  // "robust" | "fixed" | "current", else Error
const char* variant_name(Variant variant);

struct DeformOptions {
  int iterations = 100;
  double tolerance_deg = 0.5;  // 0 runs every iteration: nothing is below it
  Variant variant = Variant::kRobust;
  // Where the iteration starts (same vertices as the input), for example the
  // labeller's straightened shape; empty: the input. Energies and figures are
  // always measured against the input.
  Vertices start;
  // Also time one factorisation of the input's Laplacian, one
  // back-substitution with it and one measurement of the result
  // (DeformResult::reference_seconds): the units `make bench` states the
  // cost of an iteration and its floor in.
  bool time_references = false;
  // Robust variant: when the result is exact but collapsed faces, run again
  // from the input with those faces relabelled (relabel_collapsed_faces.h,
  // or where that is not kept, cut again: recut_collapsed_faces.h), keep the
  // run that collapses less, and repeat while one is kept (at most ten
  // rounds; docs/design.md section 2.6, stage 8).
  bool relabel_collapsed = true;
  // Robust variant, from 100,000 triangles on (kUntangleNewtonFrom): those
  // further runs start from the result they would improve instead of the
  // input, its charts moved past the relabelled faces and untangled around
  // them (flatten_near, flatten_stage.h). Several times faster at a million
  // triangles, about as much collapsed, the edge and area errors up to a
  // sixth higher (docs/design.md section 2.6, stage 8).
  bool rerun_from_result = false;
  // Robust variant: a flattening that collapses more than this share of the
  // area is refused (the continuous stage goes on instead).
  double max_collapsed_share = 0.12;
  // Robust variant: a run that ends without an exact polycube is run once
  // more with that share raised to one half, and kept when it is exact;
  // still not exact, once more with faces of opposite labels parted where
  // they meet across an edge the input does not fold (keep_opposites_apart.h)
  // (docs/design.md section 2.6, stage 9); false keeps the first run.
  bool last_resort = true;
  // Robust variant: an exact result's edge and area errors are lowered last
  // inside its flat charts (polish_stage.h, docs/design.md section 2.6,
  // stage 10), as one more iteration when the limit leaves room for it.
  bool polish = true;
  // Robust variant: a mesh of at least kCoarseFromRatio times this many
  // triangles is decimated to about this many, its charts kept, deformed
  // there and carried back (coarse_to_fine.h, docs/design.md section 2.8);
  // 0 deforms every mesh at its own resolution.
  int coarse_triangles = 50'000;
  // Robust variant: a flattening attempt whose first flat solve turns
  // triangles over untangles that solve at once (untangle_flat_charts.h),
  // without the rounds that collapse them first (flatten_charts.h).
  bool untangle_first_solve = false;
  // Robust variant, stage 8: false sets untangle_first_solve for every
  // further run after a kept run whose rounds were refused (a run after the
  // first, kept by untangling its first solve): the coarse route's coarse
  // run (docs/design.md section 2.8).
  bool retry_refused_rounds = true;
  // Robust variant, stage 5: a result untangled when flattening is
  // untangled once more from where the relaxation left it when more than
  // this share of the area is still collapsed: the second pass starts from
  // a better shape and reopens triangles the first put on a line (turbine:
  // 2.2% to 0.5%), at the cost of the first pass again (bunny00: 0.32%
  // either way, twice the time). The coarse route's coarse run sets its own
  // (kCoarseUntangleAgainAbove, coarse_to_fine.h).
  double untangle_again_above = 0.005;
  // Polled after every iteration, of the first run (as its callback is) and
  // of those further runs, which the callback does not see, and inside the
  // stages whose steps take minutes at a million triangles (every round and
  // Newton iteration of an untangling, every step of the polish): returning
  // true stops the run at the iteration it is in, keeping what it had; a
  // further run stopped is not kept (Esc in Blender).
  std::function<bool()> stop_requested;
};

// Stage 9 (docs/design.md section 2.6): a run that ends without an exact
// polycube is run once more, its flattening refused only above this share
// of the area collapsed. An exact polycube with holes beats no polycube
// (such a run returns its best state, often the input), and the further
// runs of stage 8 then reopen what they can.
constexpr double kLastResortCollapsedShare = 0.5;

struct PhaseSeconds {
  double total = 0, assemble = 0, factorize = 0, rotations = 0, solve = 0, measure = 0;
};

// Where the run's time goes, by stage of the robust variant (docs/design.md
// section 2.6), each stage's seconds without the others': the set-up before
// the first iteration (triangulating, analysing, assembling and factorising
// the input's Laplacian), fitting, the continuous fallback, relaxing flat
// charts (each an iteration's own time), the attempts at flattening, the
// untangling of flat shapes (untangle_step.h, within a flattening attempt or
// a relaxing iteration), the measurement of every iteration and the polish
// of the result (polish_stage.h: one call, an iteration when it keeps a
// step). What is left of `seconds.total` is the result's own measurement
// (conclude). The other variants count every iteration as continuous.
struct StageCost {
  int count = 0;  // iterations, or calls for `flatten` and `untangle`
  double seconds = 0.0;
};
struct StageSeconds {
  StageCost set_up, fit, continuous, relax, flatten, untangle, measure, polish;
  int current_steps = 0;  // continuous steps that needed the current mesh's Laplacian
};

struct DeformResult {
  Vertices positions;
  std::vector<int> labels;  // per polygon face, unlabelled ones replaced by their nearest axis
  Figures figures;          // of `positions`, against `labels`
  // Against the labels the caller gave (unlabelled faces: their nearest
  // axis); the same as `figures` unless the solver relabelled faces.
  Figures given_labels_figures;
  int input_folded_edges = 0;  // see quality.h; no robust result has more
  int iterations = 0;
  // The iteration whose positions are returned: `iterations`, except when
  // the last state of a robust run folds more edges than the input or flips
  // more faces than the labels did at the start; then the latest state that
  // does neither (0: the input).
  int kept_iteration = 0;
  bool converged = false;  // largest normal deviation below the tolerance, and not degenerate (see deformation.h)
  bool stopped = false;    // the callback asked to stop
  std::string failure;     // why the solver broke off after some iterations; empty otherwise
  int unlabelled_faces = 0;
  int triangles = 0;
  // Polygon faces (ids into the input's faces, ascending) that end above the
  // tolerance, and those of them that are flipped (a visible fold). A polygon
  // is listed when any of its triangles is; collapsed triangles are not.
  std::vector<int> unconverged_faces;
  std::vector<int> flipped_faces;
  // Polygon faces whose label the `robust` variant changed because they could
  // not reach its axis without folding (relabel_stalled_faces.h); `labels` holds the
  // new ones and the figures are measured against them.
  std::vector<int> relabelled_faces;
  // Iterations of the robust variant's second run with collapsed faces
  // relabelled (DeformOptions::relabel_collapsed), when it was kept; it
  // counts as one iteration in `iterations`, the last. 0 otherwise.
  int second_run_iterations = 0;
  // Whether the result comes from stage 9's run (DeformOptions::max_collapsed_share):
  // the first run did not end exact.
  bool last_resort = false;
  // The `robust` variant's iteration at which every chart became exactly
  // flat (flatten_charts.h), 0 when it did not; the triangles it collapsed
  // on purpose there to undo folds.
  int flat_iteration = 0;
  int collapsed_on_purpose = 0;
  // Whether collapsed or turned-over triangles of a flat result were opened
  // inside their charts (untangle_flat_charts.h) in the result returned.
  bool untangled = false;
  // Steps of the polish (DeformOptions::polish) kept; when more than 0 it
  // counts as one iteration in `iterations`, the last.
  int polish_steps = 0;
  // The triangles of the coarse mesh the result was deformed through
  // (DeformOptions::coarse_triangles; 0: deformed at its own resolution),
  // and the iterations before the run that gave the result (the mesh's own
  // run up to its hand-over and the coarse run's, or those of a route not
  // taken), counted in `iterations`: that run's follow them, with the
  // iteration limit to themselves.
  int coarse_triangles = 0, coarse_iterations = 0;
  // The run stopped at its first flattening attempt to hand the mesh to the
  // coarse route (Deformation::hand_over_unflat); not in a result returned.
  bool handed_over = false;
  // Every attempt at flattening, kept or refused: why a run did not become
  // exact (too much area collapsed, or folds left after every round).
  struct FlattenAttempt {
    int iteration = 0, rounds = 0, folds_left = 0;
    double collapsed_area = 0.0;  // share of the input's area
    bool kept = false;
    // Its cost: numeric factorisations of the flat solves, minimisation
    // rounds untangling a refused flat solve (untangle_flat_charts.h; 0:
    // not untangled), seconds of the whole attempt and of the untangling.
    int factorizations = 0, untangle_rounds = 0;
    double seconds = 0.0, untangle_seconds = 0.0;
  };
  std::vector<FlattenAttempt> flatten_attempts;
  int factorizations = 0;  // numeric factorisations of a Laplacian
  // Back-substitutions for three right-hand sides, or three of one: one per
  // solve with the input's (or the current mesh's) factorisation, per global
  // solve of the three flat-chart systems, per conjugate-gradient step. The
  // small local solves of flattening (ChartPlanes::solve_near) are not
  // counted, like their factorisations.
  int back_substitutions = 0;
  // The input's factorisation used (sparse_cholesky.h); a run that never
  // made one (from near a polycube) reports the first of the runs it adds
  // the cost of (add_cost) that did.
  std::string solver;
  PhaseSeconds seconds;
  StageSeconds stages;
  // With DeformOptions::time_references: one numeric factorisation of the
  // input's Laplacian, one back-substitution (3 right-hand sides) with it and
  // one measurement of every figure of the result, in seconds (the median of
  // three); 0 otherwise.
  double reference_factorize_seconds = 0.0, reference_solve_seconds = 0.0, reference_measure_seconds = 0.0;
};

// Adds `from`'s cost (its seconds, stages, factorisations and
// back-substitutions) to `into`: a run made for another counts in its time.
void add_cost(DeformResult& into, const DeformResult& from);

// Called after each iteration with its number (from 1), the positions and their
// figures; returning false stops the run, keeping what is done.
using IterationCallback = std::function<bool(int iteration, const Vertices& positions, const Figures& figures)>;

// `callback` for a run whose iterations follow `offset` already seen: it
// sees them numbered on from there (empty when `callback` is).
IterationCallback numbered_from(const IterationCallback& callback, int offset);

// Labels are per polygon face, -1..5. Throws Error on input check_input rejects
// and when a linear solve fails.
// Works in the unit box (unit_box.h): the same model at any scale gives the
// same iterations and figures, and positions in the input's units.
DeformResult deform(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options = {},
                    const IterationCallback& callback = {});

// deform() itself, on a mesh already in the unit box (deform_any_scale.cpp
// moves it there and back).
DeformResult deform_in_unit_box(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                                const IterationCallback& callback);

}  // namespace polycube
