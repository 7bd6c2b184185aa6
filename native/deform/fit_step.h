// The robust variant's first stage (robust_run.h, docs/design.md section
// 2.6): fit every triangle's *input* shape, turned onto its label's axis with
// the best in-plane twist (fitted_rotations.h), by one global solve with the
// input's Laplacian factorised once, then step there fold-free. Iterated, it
// gives an as-rigid-as-possible shape close to the polycube, which cuts edge
// and area error; it is a starting point for flatten_stage.h, not exact.
//
// Inputs: a RobustRun (its positions d.x and their states). Output: the
// fold-free step (not yet taken).
#pragma once

#include "deform/fold_free_step.h"

namespace polycube {

struct RobustRun;

FoldFreeStep fit_step(RobustRun& run);

}  // namespace polycube
