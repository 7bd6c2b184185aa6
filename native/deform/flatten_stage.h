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

#include "mesh/mesh.h"

namespace polycube {

struct RobustRun;

constexpr int kMaxFlattenAttempts = 3;

void flatten_stage(RobustRun& run, int iteration);

// The flattening of a run whose labels differ on a few faces from those of
// `near`, an exact, fold-free polycube (stage 8's further runs at scale,
// docs/design.md section 2.6): `near` put on the run's charts
// (snap_to_charts.h) and untangled by local rounds around what that leaves
// without room (untangle_step.h), instead of fitting and flattening from the
// input, whose untangling is several factorisations of the whole mesh per
// round. Kept, as flatten_stage keeps a flat shape, when it is fold-free
// and collapses no more than a flattening may; returns whether it was kept.
// Not counted among the run's kMaxFlattenAttempts: a run that does not keep
// it goes on from the input as any other. The input's factor is freed
// meanwhile, as by flatten_stage (fandisk refined 16 times: peak 697 -> 625
// MiB), and factorised again when it is not kept.
bool flatten_near(RobustRun& run, const Vertices& near, int iteration);

}  // namespace polycube
