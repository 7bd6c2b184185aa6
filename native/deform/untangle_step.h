// A flat shape's collapsed and turned-over triangles opened inside their
// charts (untangle_flat_charts.h), placed like every solve of the robust
// variant (robust_run.h) and measured: the step flatten_stage.h takes when
// the linear flat solve is refused, and relax_stage.h once relaxed.
//
// Inputs: a RobustRun (its mesh and labels) and `flat`, an exact polycube
// of them; `bound`: the collapses past which the caller refuses the result
// (then untangling stops as soon as that is certain, and the step is not
// fold-free, its shape not computed). Output: the opened shape, its states,
// and whether it is fold-free: nothing turned over and no more edges folded
// than in the input. `factored`: the flat charts whose factors the caller
// holds; at Newton's scale they are freed before the first global round
// (their orderings kept), not held beside Newton's factor, several times
// their size (bunny00 refined 4 times: 113 of the 415 MB of factors at the
// peak), and refactorised to the same factors, bit for bit, if they are
// needed again. Local rounds alone leave them.
#pragma once

#include "deform/quality.h"
#include "deform/untangle_flat_charts.h"

namespace polycube {

class ChartPlanes;
struct RobustRun;

struct UntangleStep {
  Vertices positions;
  FaceStates states;  // of `positions`
  bool fold_free = false;
  int rounds = 0;  // of untangle_flat_charts
};

// Its time is a stage of its own (StageSeconds::untangle). `start`:
// untangle_flat_charts's.
UntangleStep untangle_step(RobustRun& run, const Vertices& flat, ChartPlanes& factored, const CollapseBound& bound,
                           UntangleStart start = UntangleStart::as_needed);

}  // namespace polycube
