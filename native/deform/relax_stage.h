// The robust variant's relaxing stage (robust_run.h, docs/design.md section
// 2.6): once every chart is flat (flatten_stage.h), one as-rigid-as-possible
// step inside the flat charts per iteration (relax_flat_charts in
// flatten_charts.h). Two flat shapes with the same charts blend into a flat
// shape, so the step is shortened as a whole until it folds or collapses
// nothing; relaxing is done when even a short step would, or once steps are
// small. Then, once each:
// - the slivers collapsed to undo the first solve's folds may have room
//   again: the same charts without those collapses, blended in as far as
//   nothing folds and fewer faces stay collapsed;
// - triangles still collapsed are opened inside their charts
//   (untangle_step.h), kept when nothing turns over, fewer are collapsed and
//   no more edges fold; then relaxed again.
//
// Inputs: a flat RobustRun (run.planes set) at `iteration`. Output: whether
// the shape moved (false: nothing more to do); run.relaxed.
#pragma once

namespace polycube {

struct RobustRun;

// A result untangled when flattening is untangled once more from where the
// relaxation left it when more than DeformOptions::untangle_again_above of
// the area is still collapsed.
bool relax_stage(RobustRun& run, int iteration);

}  // namespace polycube
