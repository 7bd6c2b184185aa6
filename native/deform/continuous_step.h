// The robust variant's continuous stage (robust_run.h, docs/design.md section
// 2.6): where flat charts are refused (the labels ask for more than slivers),
// the paper's step goes on, fold-free.
//
// The step uses the input's Laplacian (one back-substitution); where that
// would fold a face it is taken with the current mesh's Laplacian instead:
// with the input's, the paper's iteration reaches collapsed faces by turning
// them over first (B0: 4 faces folded at iteration 4 of `fixed`); the
// current metric's does not. Below kApproximateCurrentSolveFrom vertices that
// system is factorised (cheap there, and the approximate target changed
// figures: bunny00 untangled 0.32% -> 9.8% collapsed); above, a few
// conjugate-gradient steps preconditioned by the input's factorisation, no
// factorisation per iteration.
//
// Inputs: a RobustRun at `iteration`. Output: the fold-free step (not yet
// taken).
#pragma once

#include <memory>

#include "deform/fold_free_step.h"
#include "linear_algebra/laplacian.h"
#include "linear_algebra/sparse_cholesky.h"

namespace polycube {

struct RobustRun;

constexpr int kApproximateCurrentSolveFrom = 50000;

// What the continuous stage keeps between iterations.
struct ContinuousFallback {
  // Built on first use (its pattern is a few MiB a million triangles).
  std::unique_ptr<Laplacian> current_laplacian;
  SparseCholesky current_factorization;
  bool current_analyzed = false;
  // The last approximate solution of its system (kApproximateCurrentSolveFrom).
  Eigen::MatrixX3d current_guess;
  // On large meshes, once the input's step folded it is tried again only
  // from this iteration on.
  int input_step_from = 0;
};

FoldFreeStep continuous_step(RobustRun& run, int iteration);

}  // namespace polycube
