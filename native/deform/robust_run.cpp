#include "deform/robust_run.h"

#ifdef __linux__
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>
#endif

#include "deform/fit_step.h"
#include "deform/flatten_charts.h"
#include "deform/flatten_stage.h"
#include "deform/relabel_stalled_faces.h"
#include "deform/relax_stage.h"
#include "deform/rotated_edges_rhs.h"
#include "linear_algebra/run_tasks.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {
namespace {

// The fitting phase ends after this many iterations at most: the fitted
// shape is as-rigid-as-possible, not exact, so it is only a starting point.
constexpr int kMaxFitIterations = 30;
// Flattening is also retried this many iterations after the last attempt,
// stalled or not.
constexpr int kRetryIterations = 10;
// Stalled: the largest deviation has not dropped by kProgress (relative) for
// kStallIterations; then faces above kRepairDeviationDeg are candidates for
// label repair (relabel_stalled_faces.h).
constexpr int kStallIterations = 10;
constexpr double kProgress = 0.01;
constexpr double kRepairDeviationDeg = 45.0;
// From this many vertices the first flattening's largest system is
// factorised during the set-up and the fitting (RobustRun::ordered_factor);
// below it that factorisation takes about what starting its thread does.
constexpr int kOrderedFactorFrom = 5'000;

}  // namespace

RobustRun::RobustRun(Deformation& deformation) : d(deformation) {
  DeformResult& result = d.result;
  // Positive weights: with negative cotangents L is indefinite and the
  // global step can fold triangles on its own (bone: 16% of the input's
  // corners are obtuse, fandisk 7%). Clamping at zero keeps L positive
  // semidefinite, and every fixed point is still an exact polycube.
  d.weights = cotangent_weights(d.mesh.vertices, d.triangles()).cwiseMax(0.0);
  d.shift = d.laplacian.assemble(d.weights, kRelativeShift);
  result.seconds.assemble += d.phase.lap();
  if (!result.converged) {
    // What needs only the positions, the labels and the Laplacian's
    // pattern: the flat charts' orderings, the start's states and the
    // first fitting step's right-hand side.
    ordered = std::make_unique<ChartPlanes>(d.n, d.triangles(), d.triangle_labels);
    const auto order_charts = [&] {
      ordered->order(d.laplacian.matrix());
      if (d.n >= kOrderedFactorFrom) {
        // At the lowest priority: it takes the time the input's
        // factorisation and the fitting's back-substitutions leave a core
        // idle, not the fitting's own (B0 refined 64 times: fitting 1.7 ->
        // 1.9 s, flattening 5.5 -> 4.4 s; B0 itself: the whole process 7%
        // faster at the same peak).
        ordered_factor = std::async(std::launch::async, [this] {
#ifdef __linux__
          setpriority(PRIO_PROCESS, static_cast<id_t>(syscall(SYS_gettid)), 19);
#endif
          ordered->factorize(d.laplacian.matrix(), 1);
        });
      }
    };
    const auto prepare_fit = [&] {
      // A run from near a polycube that ends there when not flat never
      // fits from the input.
      if (d.near.size() > 0 && d.near_start.or_nothing) return;
      state = d.quality.face_states(d.x);
      first_fit_rhs = fitted_rhs(d.mesh.vertices, d.x, d.triangles(), d.triangle_labels, d.weights, d.shift);
    };
    if (d.factorization_released) {
      // Nothing factorised meanwhile (a run from near a polycube): the
      // axes' orderings take both threads (stage 8's further runs at a
      // million triangles: 1.6 s each, most of their set-up).
      order_charts();
      prepare_fit();
    } else {
      // On a second thread, beside the input's factorisation.
      run_tasks(2, [&](int i) {
        if (i == 0) return d.factorization.factorize(d.laplacian.matrix());
        order_charts();
        prepare_fit();
      });
    }
  } else {
    state = d.quality.face_states(d.x);
  }
  result.seconds.factorize += d.phase.lap();
  diagonal = (d.mesh.vertices.colwise().maxCoeff() - d.mesh.vertices.colwise().minCoeff()).norm();
}

RobustRun::RobustRun(Deformation& deformation, const Assembled&) : d(deformation) {
  state = d.quality.face_states(d.x);
  diagonal = (d.mesh.vertices.colwise().maxCoeff() - d.mesh.vertices.colwise().minCoeff()).norm();
}

const std::vector<std::vector<int>>& RobustRun::face_adjacency() {
  if (adjacency_.empty()) adjacency_ = face_neighbours(mesh_adjacency(d.mesh.faces, d.n), d.mesh.faces.count());
  return adjacency_;
}

FoldFreeStep RobustRun::controlled_step(const Vertices& target) {
  // Kept between steps only on large meshes: on small ones a step builds
  // its own in no time, and keeping it raised B0's peak by 1.3 MiB.
  const bool keep = d.n >= kApproximateCurrentSolveFrom;
  FoldFreeStep step =
      fold_free_step(d.x, state, target, d.triangles(), d.quality, kMaxHalvings, keep ? &step_incidence : nullptr);
  step.positions = place_components(step.positions, step.positions, d.parts, d.centroids);
  return step;
}

std::unique_ptr<ChartPlanes> RobustRun::charts_like(const ChartPlanes& same_charts) {
  auto planes = std::make_unique<ChartPlanes>(d.n, d.triangles(), d.triangle_labels);
  planes->use_chart_factors(chart_factors ? *chart_factors : same_charts);
  chart_factors.reset();  // what it kept is shared by `planes` now, or no longer needed
  return planes;
}

std::unique_ptr<ChartPlanes> robust_iteration(Deformation& d) {
  RobustRun run(d);
  d.begin_iterations();
  DeformResult& result = d.result;
  bool exact = false;  // fitting done
  int fit_iterations = 0, since_progress = 0, first = 1;
  // From a polycube of nearly the same labels (stage 8 at scale), its first
  // iteration when that flattens; else from the input as any run.
  StageCost near_rest;  // what that iteration spends besides its flattening and measurement: nothing to speak of
  if (d.near.size() > 0 && d.options.iterations > 0 && !result.converged) {
    d.stage = &near_rest;
    const bool flat = flatten_near(run, d.near, 1);
    d.near = Vertices();  // read once: not held through the run (29 MB at a million triangles)
    if (flat) {
      exact = true;
      first = 2;
      if (!d.finish_iteration(1, &run.state)) return std::move(run.planes);
    } else if (d.near_start.or_nothing) {
      return std::move(run.planes);
    }
  }
  double best_max = run.state.max_deviation_deg;
  for (int iteration = first; iteration <= d.options.iterations && (!result.converged || (run.planes && !run.relaxed));
       ++iteration) {
    d.stage = run.planes ? &result.stages.relax : exact ? &result.stages.continuous : &result.stages.fit;
    if (run.planes) {
      // run.state is the relaxed shape's, measured by the stage's step control.
      if (!relax_stage(run, iteration) || !d.finish_iteration(iteration, &run.state)) break;
      continue;
    }
    if (!exact) ++fit_iterations;
    FoldFreeStep step = exact ? continuous_step(run, iteration) : fit_step(run);
    const double step_size = (step.positions - d.x).rowwise().norm().maxCoeff() / run.diagonal;
    d.x = std::move(step.positions);
    run.state = std::move(step.states);

    if (!exact && (step_size < kFitStepTolerance || fit_iterations >= kMaxFitIterations)) {
      exact = true;
      flatten_stage(run, iteration);
    }
    // Stalled: the largest deviation has not improved for a while. Faces
    // held back by the step control are the usual reason: repair their
    // labels where a neighbour's label fits them (relabel_stalled_faces.h).
    if (run.state.max_deviation_deg < best_max * (1.0 - kProgress)) {
      best_max = run.state.max_deviation_deg;
      since_progress = 0;
    } else if (exact && ++since_progress >= kStallIterations) {
      since_progress = 0;
      std::vector<int> labels = result.labels;
      const std::vector<int> changed =
          relabel_stalled_faces(d.x, d.triangulation, run.face_adjacency(), run.state, kRepairDeviationDeg, labels);
      if (!changed.empty()) {
        d.set_labels(std::move(labels));
        run.state = d.quality.face_states(d.x);
        best_max = run.state.max_deviation_deg;
      }
      flatten_stage(run, iteration);
    } else if (exact && iteration - run.last_attempt >= kRetryIterations) {
      // The continuous iteration can keep improving slowly for a long
      // time while a few folds blocked the last attempt (fandisk: 4 folds
      // at iteration 9, then no stall until iteration 100).
      flatten_stage(run, iteration);
    }
    if (result.handed_over || !d.finish_iteration(iteration, &run.state)) break;
  }
  return std::move(run.planes);
}

}  // namespace polycube
