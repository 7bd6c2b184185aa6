#include "deform/fit_step.h"

#include "deform/robust_run.h"
#include "deform/rotated_edges_rhs.h"

namespace polycube {

FoldFreeStep fit_step(RobustRun& run) {
  Deformation& d = run.d;
  Eigen::MatrixX3d rhs;
  if (run.first_fit_rhs.size() > 0)
    rhs.swap(run.first_fit_rhs);  // made beside the input's factorisation (RobustRun)
  else
    rhs = fitted_rhs(d.mesh.vertices, d.x, d.triangles(), d.triangle_labels, d.weights, d.shift);
  d.result.seconds.rotations += d.phase.lap();
  FoldFreeStep step = run.controlled_step(d.solve(d.factorization, rhs));
  d.result.seconds.solve += d.phase.lap();
  return step;
}

}  // namespace polycube
