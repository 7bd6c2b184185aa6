#include "deform/flatten_stage.h"

#include "deform/flatten_charts.h"
#include "deform/robust_run.h"
#include "deform/snap_to_charts.h"
#include "deform/untangle_step.h"

namespace polycube {
namespace {

// A flat shape kept at `iteration`: the run's positions, states and planes;
// from here on only the flat charts' systems are solved.
void keep_flat(RobustRun& run, Vertices positions, FaceStates states, std::unique_ptr<ChartPlanes> planes,
               int iteration) {
  run.d.x = std::move(positions);
  run.state = std::move(states);
  run.planes = std::move(planes);
  run.continuous.current_factorization.release();
  run.d.result.flat_iteration = iteration;
}

}  // namespace

void flatten_stage(RobustRun& run, int iteration) {
  if (run.planes || run.flatten_attempts >= kMaxFlattenAttempts) return;
  Deformation& d = run.d;
  DeformResult& result = d.result;
  ++run.flatten_attempts;
  run.step_incidence.reset();  // not held through the factorisations
  const StageTimer timer(result.stages.flatten, d.set_apart);
  Stopwatch clock;  // the attempt's own seconds
  run.last_attempt = iteration;
  d.release_factorization();  // restored below unless the charts end flat
  if (run.ordered_factor.valid()) run.ordered_factor.get();
  const Placement place = [&d](const Eigen::MatrixX3d& solution) { return d.place(solution); };
  FlatCharts flat = flatten_charts(d.mesh.vertices, d.x, d.triangles(), d.triangle_labels, d.weights,
                                   d.laplacian.matrix(), d.shift, d.quality, place, d.options.max_collapsed_share,
                                   d.options.untangle_first_solve ? 1 : kFlattenRounds, run.ordered.get(),
                                   d.hand_over_unflat);
  if (run.ordered) result.factorizations += run.ordered->factorizations();
  run.ordered.reset();  // its orderings (and factor) are the attempt's planes' now
  run.chart_factors = std::move(flat.charts);
  result.seconds.factorize += d.phase.lap();  // nearly all of it
  result.factorizations += flat.planes->factorizations();
  result.back_substitutions += flat.planes->solves();
  result.flatten_attempts.push_back(
      {iteration, flat.rounds, flat.states.flipped_count, flat.collapsed_area, flat.found});
  DeformResult::FlattenAttempt& attempt = result.flatten_attempts.back();
  attempt.factorizations = flat.planes->factorizations();
  if (!flat.found && d.hand_over_unflat) {
    result.handed_over = true;
    run.chart_factors.reset();
    attempt.seconds = clock.lap();
    return;
  }
  if (!flat.found && flat.first_positions.size() > 0) {
    CollapseBound bound;
    bound.area = d.options.max_collapsed_share;  // refused above, below
    UntangleStep opened = untangle_step(run, flat.first_positions, *flat.planes, bound);
    attempt.untangle_seconds = d.phase.lap();
    attempt.untangle_rounds = opened.rounds;
    result.seconds.solve += attempt.untangle_seconds;
    if (opened.fold_free && d.quality.collapsed_area_fraction(opened.states) <= d.options.max_collapsed_share) {
      flat.positions = std::move(opened.positions);
      flat.states = std::move(opened.states);
      flat.planes = run.charts_like(*flat.planes);
      flat.found = attempt.kept = true;
      result.untangled = true;
      d.untangled_at = iteration;
    }
  }
  if (!flat.found) {
    run.chart_factors.reset();  // not beside the input's factor
    d.restore_factorization();  // the continuous stage goes on
    // Charged here: left in the phase, the iteration's measurement would take
    // it, and the iteration's stage, losing it twice, could fall below zero.
    result.seconds.factorize += d.phase.lap();
    attempt.seconds = clock.lap();
    return;
  }
  keep_flat(run, std::move(flat.positions), std::move(flat.states), std::move(flat.planes), iteration);
  result.collapsed_on_purpose = flat.collapsed_on_purpose;
  attempt.seconds = clock.lap();
}

bool flatten_near(RobustRun& run, const Vertices& near, int iteration) {
  Deformation& d = run.d;
  DeformResult& result = d.result;
  if (run.planes) return false;
  const StageTimer timer(result.stages.flatten, d.set_apart);
  Stopwatch clock;
  if (run.ordered_factor.valid()) run.ordered_factor.get();
  d.release_factorization();  // not beside Newton's; restored below unless kept
  // The run's charts, with the orderings (and the factor) made beside the
  // input's factorisation; `ordered` stays for the run's own flattening.
  auto planes = std::make_unique<ChartPlanes>(d.n, d.triangles(), d.triangle_labels);
  if (run.ordered) planes->use_chart_factors(*run.ordered);
  const Vertices flat = snap_to_charts(near, *planes);
  CollapseBound bound;
  bound.area = d.options.max_collapsed_share;
  UntangleStep opened = untangle_step(run, flat, *planes, bound, d.near_start.untangle);
  const double untangle_seconds = d.phase.lap();
  result.seconds.solve += untangle_seconds;
  const double collapsed = opened.fold_free ? d.quality.collapsed_area_fraction(opened.states) : 1.0;
  const bool kept = opened.fold_free && collapsed <= d.options.max_collapsed_share;
  result.flatten_attempts.push_back({iteration, 0, opened.fold_free ? 0 : opened.states.flipped_count,
                                     opened.fold_free ? collapsed : 0.0, kept});
  DeformResult::FlattenAttempt& attempt = result.flatten_attempts.back();
  attempt.untangle_rounds = opened.rounds;
  attempt.untangle_seconds = untangle_seconds;
  if (!kept) {
    if (!d.near_start.or_nothing) d.restore_factorization();  // the run goes on from the input
    result.seconds.factorize += d.phase.lap();
    attempt.seconds = clock.lap();
    return false;
  }
  run.ordered.reset();
  run.step_incidence.reset();
  keep_flat(run, std::move(opened.positions), std::move(opened.states), std::move(planes), iteration);
  result.untangled = true;
  d.untangled_at = iteration;
  run.last_attempt = iteration;
  attempt.seconds = clock.lap();
  return true;
}

}  // namespace polycube
