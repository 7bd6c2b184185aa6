#include "deform/continuous_step.h"

#include "deform/poisson_rhs.h"
#include "deform/robust_run.h"
#include "linear_algebra/preconditioned_cg.h"

namespace polycube {
namespace {

// On large meshes (approximate solves), once the input's step folded it is
// tried again only after this many iterations: where it folds once it folds
// on (every continuous step of armadillo and bunny00), and a try costs a
// solve and a step control.
constexpr int kRetryInputStepAfter = 10;
// At most this many preconditioned conjugate-gradient steps (back-substitutions
// with the input's factorisation), fewer once the residual is this small.
constexpr int kCurrentSolveSteps = 2;
constexpr double kCurrentSolveTolerance = 1e-6;

}  // namespace

FoldFreeStep continuous_step(RobustRun& run, int iteration) {
  Deformation& d = run.d;
  DeformResult& result = d.result;
  ContinuousFallback& c = run.continuous;
  const bool approximate_current = d.n >= kApproximateCurrentSolveFrom;
  FoldFreeStep step;
  const bool input_step = iteration >= c.input_step_from;
  if (input_step) {
    const Eigen::MatrixX3d rhs = poisson_rhs(d.x, d.triangles(), d.weights, d.triangle_labels) + d.shift * d.x;
    result.seconds.rotations += d.phase.lap();
    step = run.controlled_step(d.solve(d.factorization, rhs));
    result.seconds.solve += d.phase.lap();
    if (approximate_current && step.limited > 0) c.input_step_from = iteration + kRetryInputStepAfter;
  }
  if (!input_step || step.limited > 0) {
    ++result.stages.current_steps;
    const CotangentWeights current = cotangent_weights(d.x, d.triangles()).cwiseMax(0.0);
    if (!c.current_laplacian) c.current_laplacian = std::make_unique<Laplacian>(d.n, d.triangles());
    const double current_shift = c.current_laplacian->assemble(current, kRelativeShift);
    result.seconds.assemble += d.phase.lap();
    const Eigen::MatrixX3d rhs = poisson_rhs(d.x, d.triangles(), current, d.triangle_labels) + current_shift * d.x;
    result.seconds.rotations += d.phase.lap();
    if (approximate_current) {
      // Warm-started from the last such solve (preconditioned_cg.h). The
      // target need not be exact: the step control keeps whatever it
      // reaches fold-free.
      if (c.current_guess.rows() != d.n) c.current_guess = d.x;
      ConjugateGradient cg = preconditioned_cg(c.current_laplacian->matrix(), rhs, d.factorization,
                                               std::move(c.current_guess), kCurrentSolveSteps, kCurrentSolveTolerance);
      result.back_substitutions += cg.iterations;
      c.current_guess = std::move(cg.solution);
      step = run.controlled_step(d.place(c.current_guess));
    } else {
      if (!c.current_analyzed) c.current_factorization.analyze(c.current_laplacian->matrix(), true);
      c.current_analyzed = true;
      c.current_factorization.factorize(c.current_laplacian->matrix());
      result.seconds.factorize += d.phase.lap();
      step = run.controlled_step(d.solve(c.current_factorization, rhs));
    }
    result.seconds.solve += d.phase.lap();
  }
  return step;
}

}  // namespace polycube
