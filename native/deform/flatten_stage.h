// The robust variant's flattening stage (robust_run.h, docs/design.md section
// 2.6): from the fitted or continuous shape, the exact polycube in one go
// (flatten_charts.h: every chart flat, slivers that would turn over
// collapsed). When the linear solve is refused (it folds or collapses too
// much), its first, global solution is flat on the same charts: untangled
// inside them (untangle_step.h) it may have room for all; untangling stops
// as soon as more area is put on a line than a kept result may collapse.
//
// Inputs: a RobustRun at `iteration`. Outputs: when a flat shape is kept,
// the run's positions, states and planes (then only the flat charts'
// systems are solved: the input's factorisations are freed); every attempt
// in DeformResult::flatten_attempts. At most kMaxFlattenAttempts per run,
// none once flat.
#pragma once

namespace polycube {

struct RobustRun;

constexpr int kMaxFlattenAttempts = 3;

void flatten_stage(RobustRun& run, int iteration);

}  // namespace polycube
