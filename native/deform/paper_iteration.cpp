#include "deform/paper_iteration.h"

#include "deform/poisson_rhs.h"

namespace polycube {

void paper_iteration(Deformation& d) {
  DeformResult& result = d.result;
  auto rebuild = [&](const Vertices& from) {
    d.weights = cotangent_weights(from, d.triangles());
    d.shift = d.laplacian.assemble(d.weights, kRelativeShift);
    result.seconds.assemble += d.phase.lap();
    d.factorization.factorize(d.laplacian.matrix());
    result.seconds.factorize += d.phase.lap();
  };
  if (d.options.variant == Variant::kFixed && !result.converged) rebuild(d.mesh.vertices);
  else result.seconds.assemble += d.phase.lap();
  d.begin_iterations();

  for (int iteration = 1; iteration <= d.options.iterations && !result.converged; ++iteration) {
    if (d.options.variant == Variant::kCurrent) rebuild(d.x);
    const Eigen::MatrixX3d rhs = poisson_rhs(d.x, d.triangles(), d.weights, d.triangle_labels) + d.shift * d.x;
    result.seconds.rotations += d.phase.lap();
    d.x = d.solve(d.factorization, rhs);
    result.seconds.solve += d.phase.lap();
    if (!d.finish_iteration(iteration)) break;
  }
}

}  // namespace polycube
