#include "deform/deform.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <memory>

#include "labels/axis.h"
#include "mesh/check_input.h"
#include "mesh/components.h"
#include "linear_algebra/cotangent_weights.h"
#include "deform/fitted_rotations.h"
#include "deform/flatten_charts.h"
#include "deform/fold_free_step.h"
#include "deform/relabel_stalled_faces.h"
#include "linear_algebra/laplacian.h"
#include "mesh/mesh_adjacency.h"
#include "labels/nearest_labels.h"
#include "deform/poisson_rhs.h"
#include "linear_algebra/preconditioned_cg.h"
#include "linear_algebra/sparse_cholesky.h"
#include "deform/rotated_edges_rhs.h"
#include "deform/untangle_flat_charts.h"
#include "mesh/triangulate.h"

namespace polycube {
namespace {

// L is singular: each component floats by a translation. A shift of eps on the
// diagonal, with eps * x_i on the right, makes the system definite and is
// exact at fixed points (L x_i = b there, so x_i still solves it); eps is far
// below L's smallest non-zero eigenvalue on any mesh we can hold in memory.
constexpr double kRelativeShift = 1e-8;

// The robust variant (deform.h). Steps of a vertex are halved at most this
// often before it is held (fold_free_step.h).
constexpr int kMaxHalvings = 6;
// The fitting phase ends when no vertex moves more than this fraction of the
// bounding box diagonal, or after this many iterations: the fitted shape is
// as-rigid-as-possible, not exact, so it is only a starting point.
constexpr int kMaxFitIterations = 30;
constexpr double kFitStepTolerance = 1e-3;
// Attempts at flattening the charts (flatten_charts.h): when the fitting
// phase ends, then when progress stalls, each after a label repair.
constexpr int kMaxFlattenAttempts = 3;
// Also retried this many iterations after the last attempt, stalled or not.
constexpr int kRetryIterations = 10;
// Stalled: the largest deviation has not dropped by kProgress (relative) for
// kStallIterations; then faces above kRepairDeviationDeg are candidates for
// label repair (relabel_stalled_faces.h).
constexpr int kStallIterations = 10;
constexpr double kProgress = 0.01;
constexpr double kRepairDeviationDeg = 45.0;
// A result untangled when flattening (untangle_flat_charts.h) is untangled
// once more from where the relaxation left it when more than this share of
// the area is still collapsed: the second pass starts from a better shape and
// reopens triangles the first put on a line (turbine: 2.2% to 0.5%), at the
// cost of the first pass again (bunny00: 0.32% either way, twice the time).
constexpr double kUntangleAgainAbove = 0.005;
// The continuous fallback's solve with the current mesh's Laplacian: exact
// (its own factorisation, every step) below this many vertices, where a
// factorisation is cheap and the approximate target changed figures (bunny00
// untangled: 0.32% -> 9.8% collapsed); above it, at most
// this many preconditioned conjugate-gradient steps (back-substitutions with
// the input's factorisation), fewer once the residual is this small.
constexpr int kApproximateCurrentSolveFrom = 50000;
constexpr int kCurrentSolveSteps = 2;
constexpr double kCurrentSolveTolerance = 1e-6;


int count(const std::vector<char>& flags) { return static_cast<int>(std::count(flags.begin(), flags.end(), 1)); }

class Stopwatch {
 public:
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Adds the time from its construction to its destruction to a stage's cost,
// and to `also`.
class StageTimer {
 public:
  StageTimer(StageCost& cost, double& also) : cost_(cost), also_(also) { ++cost_.count; }
  ~StageTimer() {
    const double seconds = clock_.lap();
    cost_.seconds += seconds;
    also_ += seconds;
  }

 private:
  StageCost& cost_;
  double& also_;
  Stopwatch clock_;
};

// Below the tolerance, and not by collapsing: collapsed triangles are left out
// of the normal figures, so a mesh squeezed flat or to a point would pass
// (the paper's `current` variant does that to armadillo and bunny00).
bool converged(const Figures& figures, double tolerance_deg, Eigen::Index triangles) {
  return figures.normal_deviation_max_deg < tolerance_deg && 2 * static_cast<Eigen::Index>(figures.collapsed_faces) < triangles;
}

}  // namespace

Variant parse_variant(const std::string& name) {
  for (Variant variant : kVariants)
    if (name == variant_name(variant)) return variant;
  throw Error("unknown variant '" + name + "': use 'robust', 'fixed' or 'current'");
}

const char* variant_name(Variant variant) {
  switch (variant) {
    case Variant::kFixed: return "fixed";
    case Variant::kCurrent: return "current";
    case Variant::kRobust: break;
  }
  return "robust";
}

DeformResult deform_in_unit_box(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                                const IterationCallback& callback) {
  check_input(mesh, &labels);
  if (options.iterations < 0) throw Error("the iteration limit must be 0 or more");
  if (!(options.tolerance_deg >= 0.0)) throw Error("the tolerance must be 0 or more degrees");
  if (options.start.size() > 0 && (options.start.rows() != mesh.vertices.rows() || !options.start.allFinite()))
    throw Error("the start positions must be finite, one row per vertex of the mesh");

  Stopwatch total, phase;
  DeformResult result;
  result.labels = labels;
  const std::vector<int> nearest = nearest_labels(mesh);
  for (size_t f = 0; f < labels.size(); ++f)
    if (labels[f] == kUnlabelled) {
      result.labels[f] = nearest[f];
      ++result.unlabelled_faces;
    }

  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  const Triangles& triangles = triangulation.triangles;
  result.triangles = static_cast<int>(triangles.rows());
  std::vector<int> triangle_labels(triangles.rows());
  for (size_t t = 0; t < triangle_labels.size(); ++t)
    triangle_labels[t] = result.labels[triangulation.face_of_triangle[t]];

  const int n = static_cast<int>(mesh.vertices.rows());
  const Components parts = components(n, triangles);
  const Eigen::MatrixX3d centroids = component_centroids(mesh.vertices, parts);
  QualityMeasure quality(mesh.vertices, triangles, triangle_labels);
  Vertices x = mesh.vertices;
  result.figures = quality.measure(x, false);  // the report's error means are the last measurement's
  result.converged = converged(result.figures, options.tolerance_deg, triangles.rows());
  result.input_folded_edges = quality.input_folded_edges();
  result.seconds.measure += phase.lap();

  // Never worse than the input (docs/design.md section 2.6): a robust run
  // whose last state folds more edges than the input, or flips more faces
  // than its labels did at the start, returns the latest state that does
  // neither; the input itself qualifies, so there is always one.
  const bool keep_acceptable = options.variant == Variant::kRobust;
  const int start_flipped = result.figures.flipped_faces;
  Vertices acceptable_x = x;
  std::vector<int> acceptable_labels = result.labels;
  const std::vector<int> filled_labels = result.labels;  // the caller's, unlabelled faces filled
  auto acceptable = [&](const Figures& f) {
    return f.flipped_faces <= start_flipped && f.folded_edges <= result.input_folded_edges;
  };
  auto consider_acceptable = [&](int iteration) {
    if (!keep_acceptable || !acceptable(result.figures)) return;
    acceptable_x = x;
    acceptable_labels = result.labels;
    result.kept_iteration = iteration;
  };
  if (options.start.size() > 0) {
    x = options.start;
    result.figures = quality.measure(x, false);
    result.converged = converged(result.figures, options.tolerance_deg, triangles.rows());
  }

  Laplacian laplacian(n, triangles);
  SparseCholesky factorization;
  factorization.analyze(laplacian.matrix(), options.variant == Variant::kCurrent);
  bool factorization_released = false;
  Eigen::MatrixX3d solution(n, 3);
  // Puts a solution back where the mesh stands: every component's centroid
  // where it was, isolated vertices where they were.
  auto place = [&](const Eigen::MatrixX3d& solution) {
    if (!solution.allFinite())
      throw Error("the linear solve gave non-finite positions at iteration " + std::to_string(result.iterations + 1));
    return place_components(solution, mesh.vertices, parts, centroids);
  };
  auto solve = [&](const SparseCholesky& factorization, const Eigen::MatrixX3d& rhs) {
    solution = factorization.solve(rhs);
    return place(solution);
  };
  // An iteration's time goes to its stage (StageSeconds), less the attempts
  // at flattening it made, which are a stage of their own.
  StageCost* stage = &result.stages.continuous;
  Stopwatch iteration_clock;
  double flattening = 0.0;
  // Measures, reports to the callback; false when the run must stop.
  // `states`: face_states(x) when the step measured them already.
  auto finish_iteration = [&](int iteration, const FaceStates* states = nullptr) {
    result.figures = states ? quality.measure(x, *states, static_cast<bool>(callback))
                            : quality.measure(x, static_cast<bool>(callback));
    result.iterations = iteration;
    result.converged = converged(result.figures, options.tolerance_deg, triangles.rows());
    consider_acceptable(iteration);
    result.seconds.measure += phase.lap();
    stage->seconds += iteration_clock.lap() - flattening;
    ++stage->count;
    flattening = 0.0;
    if (callback && !callback(iteration, x, result.figures)) {
      result.stopped = true;
      return false;
    }
    phase.lap();  // time spent in the callback belongs to the caller
    iteration_clock.lap();
    return true;
  };

  int untangled_at = 0;  // the iteration whose positions were untangled
  // A solve that breaks down after some iterations (the paper's `current`
  // variant on armadillo: its triangles degenerate until the Laplacian is
  // singular) ends the run with what was done, not with nothing.
  try {
    if (options.variant == Variant::kRobust) {
      // Positive weights: with negative cotangents L is indefinite and the
      // global step can fold triangles on its own (bone: 16% of the input's
      // corners are obtuse, fandisk 7%). Clamping at zero keeps L positive
      // semidefinite, and every fixed point is still an exact polycube.
      const CotangentWeights weights = cotangent_weights(mesh.vertices, triangles).cwiseMax(0.0);
      const double shift = laplacian.assemble(weights, kRelativeShift);
      result.seconds.assemble += phase.lap();
      if (!result.converged) factorization.factorize(laplacian.matrix());
      result.seconds.factorize += phase.lap();
      // The Laplacian of the current mesh, for the steps the input's cannot
      // take; built on first use (its pattern is a few MiB a million triangles).
      std::unique_ptr<Laplacian> current_laplacian;
      SparseCholesky current_factorization;
      bool current_analyzed = false;
      // The last approximate solution of its system (kApproximateCurrentSolveFrom).
      const bool approximate_current = n >= kApproximateCurrentSolveFrom;
      Eigen::MatrixX3d current_guess;
      int input_step_from = 0;

      FaceStates state = quality.face_states(x);
      const std::vector<std::vector<int>> adjacency = face_neighbours(mesh_adjacency(mesh.faces, n), mesh.faces.count());
      const double diagonal = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();

      // Fold-free steps (fold_free_step.h), put back on the components'
      // centroids, which per-vertex steps move a little.
      auto controlled_step = [&](const Vertices& target) {
        FoldFreeStep step = fold_free_step(x, state, target, triangles, quality, kMaxHalvings);
        step.positions = place_components(step.positions, step.positions, parts, centroids);
        return step;
      };

      // Moves x towards a flat shape on the same charts (two such shapes blend
      // into one), the whole step halved until nothing folds and no more
      // faces, or with `fewer` fewer faces, are collapsed. Returns the step
      // over the bounding box diagonal, negative when no step qualifies.
      auto blend_towards = [&](const Vertices& target, bool fewer) {
        const int collapsed = count(state.collapsed);
        for (int halving = 0; halving <= kMaxHalvings; ++halving) {
          Vertices next = x + std::ldexp(1.0, -halving) * (target - x);
          FaceStates next_state = quality.face_states(next);
          const int next_collapsed = count(next_state.collapsed);
          if (next_state.flipped_count == 0 && (fewer ? next_collapsed < collapsed : next_collapsed <= collapsed)) {
            const double size = (next - x).rowwise().norm().maxCoeff() / diagonal;
            x = std::move(next);
            state = std::move(next_state);
            return size;
          }
        }
        return -1.0;
      };

      // A flat shape's collapsed and turned-over triangles opened inside
      // their charts (untangle_flat_charts.h), placed like every solve;
      // fold-free when nothing is turned over and no more edges fold than
      // in the input.
      struct Opened {
        Vertices positions;
        FaceStates states;
        bool fold_free = false;
      };
      auto untangle_from = [&](const Vertices& flat_start) {
        Opened opened;
        opened.positions = place(untangle_flat_charts(mesh.vertices, flat_start, triangles, triangle_labels).positions);
        opened.states = quality.face_states(opened.positions);
        opened.fold_free = opened.states.flipped_count == 0 &&
                           quality.measure(opened.positions, opened.states, false).folded_edges <=
                               result.input_folded_edges;
        return opened;
      };

      // Phase 3 (flatten_charts.h): the exact polycube, every chart flat,
      // fold-free; then relaxed inside the flat charts.
      std::unique_ptr<ChartPlanes> planes;
      bool relaxed = false, uncollapsed = false, untangle_tried = false;
      int flatten_attempts = 0, last_attempt = 0;
      auto try_flatten = [&](int iteration) {
        if (planes || flatten_attempts >= kMaxFlattenAttempts) return;
        ++flatten_attempts;
        const StageTimer timer(result.stages.flatten, flattening);
        last_attempt = iteration;
        FlatCharts flat = flatten_charts(mesh.vertices, x, triangles, triangle_labels, weights, laplacian.matrix(),
                                         shift, quality, place);
        result.seconds.factorize += phase.lap();  // nearly all of it
        result.factorizations += flat.planes->factorizations();
        result.flatten_attempts.push_back(
            {iteration, flat.rounds, flat.states.flipped_count, flat.collapsed_area, flat.found});
        if (!flat.found && flat.first_positions.size() > 0) {
          // Refused: the linear solve folds or collapses too much. Its
          // first, global solution is flat on the same charts: untangled
          // inside them (untangle_flat_charts.h) it may have room for all.
          Opened opened = untangle_from(flat.first_positions);
          result.seconds.solve += phase.lap();
          if (opened.fold_free && quality.collapsed_area_fraction(opened.states) <= kMaxCollapsedAreaFraction) {
            flat.positions = std::move(opened.positions);
            flat.states = std::move(opened.states);
            flat.planes = std::make_unique<ChartPlanes>(n, triangles, triangle_labels);
            flat.found = true;
            result.untangled = true;
            untangled_at = iteration;
          }
        }
        if (!flat.found) return;
        x = std::move(flat.positions);
        state = std::move(flat.states);
        planes = std::move(flat.planes);
        // From here on only the flat charts' systems are solved.
        factorization.release();
        factorization_released = true;
        current_factorization.release();
        result.flat_iteration = iteration;
        result.collapsed_on_purpose = flat.collapsed_on_purpose;
      };

      bool exact = false;
      int fit_iterations = 0, since_progress = 0;
      double best_max = state.max_deviation_deg;
      for (int iteration = 1; iteration <= options.iterations && (!result.converged || (planes && !relaxed));
           ++iteration) {
        stage = planes ? &result.stages.relax : exact ? &result.stages.continuous : &result.stages.fit;
        if (planes) {
          // Relaxing the flat polycube. Two flat shapes with the same charts
          // blend into a flat shape, so the step is shortened as a whole
          // until it folds or collapses nothing; the relaxation stops when
          // even a short step would, or once steps are small.
          const Vertices target = relax_flat_charts(mesh.vertices, x, triangles, triangle_labels, weights,
                                                    laplacian.matrix(), shift, *planes, place);
          const double step_size = blend_towards(target, false);
          bool found = step_size >= 0.0;
          if (found) relaxed = step_size < kFitStepTolerance;
          result.seconds.solve += phase.lap();
          // Once relaxed, the slivers collapsed to undo the first solve's
          // folds may have room again: the same charts without those
          // collapses, blended in as far as nothing folds and fewer faces
          // stay collapsed (both shapes are flat on the same charts).
          if ((!found || relaxed) && !uncollapsed && result.collapsed_on_purpose > 0) {
            uncollapsed = true;
            auto free_planes = std::make_unique<ChartPlanes>(n, triangles, triangle_labels);
            const Vertices free_target = relax_flat_charts(mesh.vertices, x, triangles, triangle_labels, weights,
                                                           laplacian.matrix(), shift, *free_planes, place);
            result.factorizations += free_planes->factorizations();
            if (blend_towards(free_target, true) >= 0.0) {
              planes = std::move(free_planes);
              found = true;
              relaxed = false;
            }
            result.seconds.factorize += phase.lap();
          }
          // Relaxed, some triangles may still be collapsed: opened inside
          // their charts (untangle_flat_charts.h), kept when nothing turns
          // over, fewer are collapsed and no more edges fold; then relaxed
          // again, as far as that collapses nothing.
          if ((!found || relaxed) && !untangle_tried && count(state.collapsed) > 0 &&
              (!result.untangled || quality.collapsed_area_fraction(state) > kUntangleAgainAbove)) {
            untangle_tried = true;
            Opened opened = untangle_from(x);
            if (opened.fold_free && count(opened.states.collapsed) < count(state.collapsed)) {
              x = std::move(opened.positions);
              state = std::move(opened.states);
              planes = std::make_unique<ChartPlanes>(n, triangles, triangle_labels);
              result.untangled = true;
              untangled_at = iteration;
              found = true;
              relaxed = false;
            }
            result.seconds.solve += phase.lap();
          }
          if (!found) break;
          if (!finish_iteration(iteration)) break;
          continue;
        }
        FoldFreeStep step;
        if (!exact) {
          // Phase 1: fit every triangle's input shape, turned onto its axis
          // (fitted_rotations.h), with the input's Laplacian factorised once.
          const Rotations rotations = fitted_rotations(mesh.vertices, x, triangles, weights, triangle_labels);
          const Eigen::MatrixX3d rhs = rotated_edges_rhs(mesh.vertices, triangles, weights, rotations) + shift * x;
          ++fit_iterations;
          result.seconds.rotations += phase.lap();
          step = controlled_step(solve(factorization, rhs));
          result.seconds.solve += phase.lap();
        } else {
          // Phase 2: the paper's step, exact at its fixed points, with the
          // input's Laplacian (fast: one back-substitution). Where that step
          // would fold faces, take the paper's step with the Laplacian of the
          // current mesh instead: with the input's, the paper's iteration
          // reaches collapsed faces by turning them over first (B0: 4 faces
          // folded at iteration 4 of `fixed`); the current metric's does not.
          // On large meshes (approximate_current), once the input's step
          // folded it is tried again only after kRetryIterations: where it
          // folds once it folds on (every continuous step of armadillo and
          // bunny00), and a try costs a solve and a step control.
          const bool input_step = iteration >= input_step_from;
          if (input_step) {
            const Eigen::MatrixX3d rhs = poisson_rhs(x, triangles, weights, triangle_labels) + shift * x;
            result.seconds.rotations += phase.lap();
            step = controlled_step(solve(factorization, rhs));
            result.seconds.solve += phase.lap();
            if (approximate_current && step.limited > 0) input_step_from = iteration + kRetryIterations;
          }
          if (!input_step || step.limited > 0) {
            ++result.stages.current_steps;
            const CotangentWeights current = cotangent_weights(x, triangles).cwiseMax(0.0);
            if (!current_laplacian) current_laplacian = std::make_unique<Laplacian>(n, triangles);
            const double current_shift = current_laplacian->assemble(current, kRelativeShift);
            result.seconds.assemble += phase.lap();
            const Eigen::MatrixX3d rhs = poisson_rhs(x, triangles, current, triangle_labels) + current_shift * x;
            result.seconds.rotations += phase.lap();
            if (approximate_current) {
              // A few conjugate-gradient steps preconditioned by the input's
              // factorisation, warm-started from the last such solve
              // (preconditioned_cg.h): back-substitutions, not a factorisation
              // per iteration. The target need not be exact: the step control
              // keeps whatever it reaches fold-free.
              if (current_guess.rows() != n) current_guess = x;
              current_guess = preconditioned_cg(current_laplacian->matrix(), rhs, factorization,
                                                std::move(current_guess), kCurrentSolveSteps, kCurrentSolveTolerance)
                                  .solution;
              step = controlled_step(place(current_guess));
            } else {
              if (!current_analyzed) current_factorization.analyze(current_laplacian->matrix(), true);
              current_analyzed = true;
              current_factorization.factorize(current_laplacian->matrix());
              result.seconds.factorize += phase.lap();
              step = controlled_step(solve(current_factorization, rhs));
            }
            result.seconds.solve += phase.lap();
          }
        }
        const double step_size = (step.positions - x).rowwise().norm().maxCoeff() / diagonal;
        x = std::move(step.positions);
        state = std::move(step.states);

        if (!exact && (step_size < kFitStepTolerance || fit_iterations >= kMaxFitIterations)) {
          exact = true;
          try_flatten(iteration);
        }
        // Stalled: the largest deviation has not improved for a while. Faces
        // held back by the step control are the usual reason: repair their
        // labels where a neighbour's label fits them (relabel_stalled_faces.h).
        if (state.max_deviation_deg < best_max * (1.0 - kProgress)) {
          best_max = state.max_deviation_deg;
          since_progress = 0;
        } else if (exact && ++since_progress >= kStallIterations) {
          since_progress = 0;
          const std::vector<int> changed = relabel_stalled_faces(x, triangulation, adjacency, state,
                                                                 kRepairDeviationDeg, result.labels);
          if (!changed.empty()) {
            for (size_t t = 0; t < triangle_labels.size(); ++t)
              triangle_labels[t] = result.labels[triangulation.face_of_triangle[t]];
            quality.set_labels(triangle_labels);
            state = quality.face_states(x);
            best_max = state.max_deviation_deg;
          }
          try_flatten(iteration);
        } else if (exact && iteration - last_attempt >= kRetryIterations) {
          // The continuous iteration can keep improving slowly for a long
          // time while a few folds blocked the last attempt (fandisk: 4 folds
          // at iteration 9, then no stall until iteration 100).
          try_flatten(iteration);
        }
        if (!finish_iteration(iteration, &state)) break;
      }
    } else {
      CotangentWeights weights;
      double shift = 0.0;
      auto rebuild = [&](const Vertices& from) {
        weights = cotangent_weights(from, triangles);
        shift = laplacian.assemble(weights, kRelativeShift);
        result.seconds.assemble += phase.lap();
        factorization.factorize(laplacian.matrix());
        result.seconds.factorize += phase.lap();
      };
      if (options.variant == Variant::kFixed && !result.converged) rebuild(mesh.vertices);
      else result.seconds.assemble += phase.lap();

      for (int iteration = 1; iteration <= options.iterations && !result.converged; ++iteration) {
        if (options.variant == Variant::kCurrent) rebuild(x);
        const Eigen::MatrixX3d rhs = poisson_rhs(x, triangles, weights, triangle_labels) + shift * x;
        result.seconds.rotations += phase.lap();
        x = solve(factorization, rhs);
        result.seconds.solve += phase.lap();
        if (!finish_iteration(iteration)) break;
      }
    }

  } catch (const Error& e) {
    if (result.iterations == 0) throw;
    result.failure = e.what();
  }
  if (keep_acceptable && result.kept_iteration != result.iterations) {
    result.untangled = result.untangled && result.kept_iteration >= untangled_at;
    x = std::move(acceptable_x);
    result.labels = std::move(acceptable_labels);
    for (size_t t = 0; t < triangle_labels.size(); ++t)
      triangle_labels[t] = result.labels[triangulation.face_of_triangle[t]];
    quality.set_labels(triangle_labels);
  } else {
    result.kept_iteration = result.iterations;
  }
  result.relabelled_faces.clear();
  for (int f = 0; f < mesh.faces.count(); ++f)
    if (result.labels[f] != filled_labels[f]) result.relabelled_faces.push_back(f);

  // The faces that did not make it, by polygon id; the same states give the figures.
  const FaceStates state = quality.face_states(x);
  {
    std::vector<char> unconverged(mesh.faces.count(), 0), flipped(mesh.faces.count(), 0);
    for (size_t t = 0; t < state.flipped.size(); ++t) {
      const int f = triangulation.face_of_triangle[t];
      if (!state.collapsed[t] && !(state.deviation_deg[t] < options.tolerance_deg)) unconverged[f] = 1;
      if (state.flipped[t]) flipped[f] = 1;
    }
    for (int f = 0; f < mesh.faces.count(); ++f) {
      if (unconverged[f]) result.unconverged_faces.push_back(f);
      if (flipped[f]) result.flipped_faces.push_back(f);
    }
    result.seconds.measure += phase.lap();
  }
  result.figures = quality.measure(x, state);
  result.converged = converged(result.figures, options.tolerance_deg, triangles.rows());
  if (!result.relabelled_faces.empty()) {
    // Against the labels the caller gave (unlabelled faces: nearest axis).
    std::vector<int> given(triangles.rows());
    for (size_t t = 0; t < given.size(); ++t) {
      const int label = labels[triangulation.face_of_triangle[t]];
      given[t] = label == kUnlabelled ? nearest[triangulation.face_of_triangle[t]] : label;
    }
    result.given_labels_figures = QualityMeasure(mesh.vertices, triangles, std::move(given)).measure(x);
  } else {
    result.given_labels_figures = result.figures;
  }
  result.factorizations += factorization.factorizations();
  result.solver = factorization.backend();
  result.seconds.total = total.lap();
  if (options.time_references) {
    // The median of three of each: one timing on a shared machine is noise.
    auto median_seconds = [&](const auto& run) {
      std::array<double, 3> seconds;
      for (double& s : seconds) {
        phase.lap();
        run();
        s = phase.lap();
      }
      std::sort(seconds.begin(), seconds.end());
      return seconds[1];
    };
    if (factorization.factorizations() > 0) {
      // Freed once the charts were flat: factorised again (untimed) for the
      // reference, after the run's peak.
      if (factorization_released) {
        factorization.analyze(laplacian.matrix());
        factorization.factorize(laplacian.matrix());
      }
      const Eigen::MatrixX3d rhs = x;
      result.reference_solve_seconds = median_seconds([&] { return factorization.solve(rhs); });
    }
    result.reference_measure_seconds = median_seconds([&] { return quality.measure(x); });
  }
  result.positions = std::move(x);
  return result;
}

}  // namespace polycube
