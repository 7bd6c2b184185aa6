#include "deform/fit_step.h"

#include "deform/fitted_rotations.h"
#include "deform/robust_run.h"
#include "deform/rotated_edges_rhs.h"

namespace polycube {

FoldFreeStep fit_step(RobustRun& run) {
  Deformation& d = run.d;
  const Eigen::MatrixX3d rhs = rotated_edges_rhs(d.mesh.vertices, d.triangles(), d.weights,
                                                 [&](Eigen::Index t) {
                                                   return fitted_rotation(d.mesh.vertices, d.x, d.triangles(),
                                                                          d.weights, d.triangle_labels, t);
                                                 }) +
                                 d.shift * d.x;
  d.result.seconds.rotations += d.phase.lap();
  FoldFreeStep step = run.controlled_step(d.solve(d.factorization, rhs));
  d.result.seconds.solve += d.phase.lap();
  return step;
}

}  // namespace polycube
