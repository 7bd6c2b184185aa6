#include "deform/relax_stage.h"

#include <algorithm>
#include <cmath>

#include "deform/flatten_charts.h"
#include "deform/robust_run.h"
#include "deform/untangle_flat_charts.h"
#include "deform/untangle_step.h"

namespace polycube {
namespace {

int count(const std::vector<char>& flags) { return static_cast<int>(std::count(flags.begin(), flags.end(), 1)); }

// Moves the run towards a flat shape on the same charts, the whole step
// halved until nothing folds and no more faces, or with `fewer` fewer
// faces, are collapsed. Returns the step over the bounding box diagonal,
// negative when no step qualifies.
double blend_towards(RobustRun& run, const Vertices& target, bool fewer) {
  Deformation& d = run.d;
  const int collapsed = count(run.state.collapsed);
  for (int halving = 0; halving <= kMaxHalvings; ++halving) {
    Vertices next = d.x + std::ldexp(1.0, -halving) * (target - d.x);
    FaceStates next_state = d.quality.face_states(next);
    const int next_collapsed = count(next_state.collapsed);
    if (next_state.flipped_count == 0 && (fewer ? next_collapsed < collapsed : next_collapsed <= collapsed)) {
      const double size = (next - d.x).rowwise().norm().maxCoeff() / run.diagonal;
      d.x = std::move(next);
      run.state = std::move(next_state);
      return size;
    }
  }
  return -1.0;
}

// Counts its factorisations (the axes collapses changed, or every axis of
// new planes) and its global solve.
Vertices relaxed_target(RobustRun& run, ChartPlanes& planes) {
  Deformation& d = run.d;
  const int factorized = planes.factorizations();
  Vertices target =
      relax_flat_charts(d.mesh.vertices, d.x, d.triangles(), d.triangle_labels, d.weights, d.laplacian.matrix(),
                        d.shift, planes, [&d](const Eigen::MatrixX3d& solution) { return d.place(solution); });
  d.result.factorizations += planes.factorizations() - factorized;
  ++d.result.back_substitutions;
  return target;
}

// Stage 5's last try: the untangling of what the relaxed charts left
// collapsed; kept only with fewer collapsed triangles. Returns whether it
// was kept (or `found` when not tried).
bool untangle_collapsed(RobustRun& run, int iteration, bool found) {
  Deformation& d = run.d;
  DeformResult& result = d.result;
  if ((found && !run.relaxed) || run.untangle_tried) return found;
  const int collapsed = count(run.state.collapsed);
  if (collapsed == 0 ||
      (result.untangled && d.quality.collapsed_area_fraction(run.state) <= d.options.untangle_again_above))
    return found;
  run.untangle_tried = true;
  CollapseBound bound;
  bound.triangles = collapsed - 1;  // kept only with fewer collapsed, below
  UntangleStep opened = untangle_step(run, d.x, *run.planes, bound);
  const int left = count(opened.states.collapsed);
  if (opened.fold_free && left < collapsed) {
    d.x = std::move(opened.positions);
    run.state = std::move(opened.states);
    run.planes = run.charts_like(*run.planes);
    result.untangled = true;
    d.untangled_at = iteration;
    found = true;
    run.relaxed = false;
    // Nothing left for the same charts without collapses to open.
    if (left == 0) run.uncollapsed = true;
  }
  result.seconds.solve += d.phase.lap();
  return found;
}

}  // namespace

bool relax_stage(RobustRun& run, int iteration) {
  Deformation& d = run.d;
  DeformResult& result = d.result;
  const double step_size = blend_towards(run, relaxed_target(run, *run.planes), false);
  bool found = step_size >= 0.0;
  if (found) run.relaxed = step_size < kFitStepTolerance;
  result.seconds.solve += d.phase.lap();
  // At scale the untangling of a few slivers is local and costs less than
  // the same charts without collapses, a factorisation per axis, which
  // opened none of them there (B0 refined 16 times: 0.11 s against 0.95 s,
  // all 80 slivers opened by the untangling): it is tried first.
  const bool untangle_first = d.triangles().rows() >= kUntangleNewtonFrom;
  if (untangle_first) found = untangle_collapsed(run, iteration, found);
  if ((!found || run.relaxed) && !run.uncollapsed && result.collapsed_on_purpose > 0) {
    run.uncollapsed = true;
    auto free_planes = run.charts_like(*run.planes);
    run.planes->release();  // not in memory beside the free planes' factors; refactorised if needed again
    const Vertices free_target = relaxed_target(run, *free_planes);
    if (blend_towards(run, free_target, true) >= 0.0) {
      run.planes = std::move(free_planes);
      found = true;
      run.relaxed = false;
    }
    result.seconds.factorize += d.phase.lap();
  }
  if (!untangle_first) found = untangle_collapsed(run, iteration, found);
  return found;
}

}  // namespace polycube
