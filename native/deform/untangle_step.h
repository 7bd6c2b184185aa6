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
// than in the input.
#pragma once

#include "deform/quality.h"
#include "deform/untangle_flat_charts.h"

namespace polycube {

struct RobustRun;

struct UntangleStep {
  Vertices positions;
  FaceStates states;  // of `positions`
  bool fold_free = false;
  int rounds = 0;  // of untangle_flat_charts
};

// Its time is a stage of its own (StageSeconds::untangle).
UntangleStep untangle_step(RobustRun& run, const Vertices& flat, const CollapseBound& bound = {});

}  // namespace polycube
