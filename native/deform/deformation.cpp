#include "deform/deformation.h"

#include <algorithm>
#include <array>

#include "labels/axis.h"
#include "labels/nearest_labels.h"

namespace polycube {

bool converged(const Figures& figures, double tolerance_deg, Eigen::Index triangles) {
  return figures.normal_deviation_max_deg < tolerance_deg &&
         2 * static_cast<Eigen::Index>(figures.collapsed_faces) < triangles;
}

namespace {

std::vector<int> filled(const std::vector<int>& labels, const std::vector<int>& nearest) {
  std::vector<int> result = labels;
  for (size_t f = 0; f < labels.size(); ++f)
    if (labels[f] == kUnlabelled) result[f] = nearest[f];
  return result;
}

std::vector<int> spread(const std::vector<int>& face_labels, const Triangulation& triangulation) {
  std::vector<int> labels(triangulation.face_of_triangle.size());
  for (size_t t = 0; t < labels.size(); ++t) labels[t] = face_labels[triangulation.face_of_triangle[t]];
  return labels;
}

}  // namespace

Deformation::Deformation(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                         const IterationCallback& callback, Vertices near_polycube)
    : mesh(mesh),
      given_labels(labels),
      options(options),
      callback(callback),
      nearest(nearest_labels(mesh)),
      filled_labels(filled(labels, nearest)),
      triangulation(triangulate(mesh.vertices, mesh.faces)),
      triangle_labels(spread(filled_labels, triangulation)),
      n(static_cast<int>(mesh.vertices.rows())),
      laplacian(n, triangulation.triangles),
      analysis(options.start.size() == 0 && near_polycube.size() == 0
                   ? std::async(std::launch::async, [this] { analyze(); })
                   : std::future<void>()),
      parts(components(n, triangulation.triangles)),
      centroids(component_centroids(mesh.vertices, parts)),
      quality(mesh.vertices, triangulation.triangles, triangle_labels),
      x(mesh.vertices),
      near(std::move(near_polycube)) {
  result.labels = filled_labels;
  result.unlabelled_faces = static_cast<int>(std::count(labels.begin(), labels.end(), kUnlabelled));
  result.triangles = static_cast<int>(triangles().rows());
  result.figures = quality.measure(x, false);  // the report's error means are the last measurement's
  result.converged = converged(result.figures, options.tolerance_deg, triangles().rows());
  result.input_folded_edges = quality.input_folded_edges();
  result.seconds.measure += phase.lap();

  keep_acceptable = options.variant == Variant::kRobust;
  start_flipped = result.figures.flipped_faces;
  acceptable_x = x;
  acceptable_labels = result.labels;
  if (options.start.size() > 0) {
    x = options.start;
    result.figures = quality.measure(x, false);
    result.converged = converged(result.figures, options.tolerance_deg, triangles().rows());
  }
  // A robust run from a start that is already a polycube (the polish's,
  // polish_stage.h) never solves with the input's Laplacian: its ordering
  // would be computed for nothing.
  const bool robust_exact = options.variant == Variant::kRobust && result.converged;
  if (analysis.valid())
    analysis.get();
  else if (near.size() > 0 && !robust_exact)
    // A run from near a polycube solves with the input's Laplacian only if
    // flatten_near is refused: otherwise its analysis and factorisation, in
    // each of stage 8's further runs at scale and in the coarse route's fine
    // run (docs/design.md section 2.8), would be made for nothing.
    factorization_released = true;
  else if (!robust_exact)
    analyze();
  stage = &result.stages.continuous;
}

void Deformation::analyze() { factorization.analyze(laplacian.matrix(), options.variant == Variant::kCurrent); }

Vertices Deformation::place(const Eigen::MatrixX3d& solution) const {
  if (!solution.allFinite())
    throw Error("the linear solve gave non-finite positions at iteration " + std::to_string(result.iterations + 1));
  return place_components(solution, mesh.vertices, parts, centroids);
}

Vertices Deformation::solve(const SparseCholesky& cholesky, const Eigen::MatrixX3d& rhs) {
  ++result.back_substitutions;
  return place(cholesky.solve(rhs));
}

void Deformation::begin_iterations() {
  result.stages.set_up.count = 1;
  result.stages.set_up.seconds = iteration_clock.lap();
}

void Deformation::release_factorization() {
  factorization.release();
  factorization_released = true;
}

void Deformation::restore_factorization() {
  if (!factorization_released) return;
  const SparseCholesky::Ordering ordering = factorization.ordering();
  factorization.analyze(laplacian.matrix(), ordering);
  factorization.factorize(laplacian.matrix());
  factorization_released = false;
}

std::vector<int> Deformation::per_triangle(const std::vector<int>& face_labels) const {
  return spread(face_labels, triangulation);
}

void Deformation::set_labels(std::vector<int> face_labels) {
  result.labels = std::move(face_labels);
  triangle_labels = per_triangle(result.labels);
  quality.set_labels(triangle_labels);
}

bool Deformation::finish_iteration(int iteration, const FaceStates* states) {
  const bool errors = static_cast<bool>(callback);
  result.figures = states ? quality.measure(x, *states, errors) : quality.measure(x, errors);
  result.iterations = iteration;
  result.converged = converged(result.figures, options.tolerance_deg, triangles().rows());
  if (keep_acceptable && result.figures.flipped_faces <= start_flipped &&
      result.figures.folded_edges <= result.input_folded_edges) {
    acceptable_x = x;
    acceptable_labels = result.labels;
    result.kept_iteration = iteration;
  }
  const double measuring = phase.lap();
  result.seconds.measure += measuring;
  result.stages.measure.seconds += measuring;
  ++result.stages.measure.count;
  stage->seconds += iteration_clock.lap() - set_apart - measuring;
  ++stage->count;
  set_apart = 0.0;
  if ((callback && !callback(iteration, x, result.figures)) || (options.stop_requested && options.stop_requested())) {
    result.stopped = true;
    return false;
  }
  phase.lap();  // time spent in the callback belongs to the caller
  iteration_clock.lap();
  return true;
}

DeformResult Deformation::conclude() {
  if (keep_acceptable && result.kept_iteration != result.iterations) {
    result.untangled = result.untangled && result.kept_iteration >= untangled_at;
    x = std::move(acceptable_x);
    set_labels(std::move(acceptable_labels));
  } else {
    result.kept_iteration = result.iterations;
  }
  result.relabelled_faces.clear();
  const int faces = mesh.faces.count();
  for (int f = 0; f < faces; ++f)
    if (result.labels[f] != filled_labels[f]) result.relabelled_faces.push_back(f);

  // The faces that did not make it, by polygon id; the same states give the figures.
  const FaceStates state = quality.face_states(x);
  {
    std::vector<char> unconverged(faces, 0), flipped(faces, 0);
    for (size_t t = 0; t < state.flipped.size(); ++t) {
      const int f = triangulation.face_of_triangle[t];
      if (!state.collapsed[t] && !(state.deviation_deg[t] < options.tolerance_deg)) unconverged[f] = 1;
      if (state.flipped[t]) flipped[f] = 1;
    }
    for (int f = 0; f < faces; ++f) {
      if (unconverged[f]) result.unconverged_faces.push_back(f);
      if (flipped[f]) result.flipped_faces.push_back(f);
    }
    result.seconds.measure += phase.lap();
  }
  result.figures = quality.measure(x, state);
  result.converged = converged(result.figures, options.tolerance_deg, triangles().rows());
  if (!result.relabelled_faces.empty()) {
    // Against the labels the caller gave (unlabelled faces: nearest axis).
    result.given_labels_figures = QualityMeasure(mesh.vertices, triangles(), per_triangle(filled_labels)).measure(x);
  } else {
    result.given_labels_figures = result.figures;
  }
  result.factorizations += factorization.factorizations();
  if (factorization.factorizations() > 0) result.solver = factorization.backend();
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
    if (factorization.factorizations() > 0 || factorization_released) {
      // Freed once the charts were flat: restored for the reference, after
      // the run's peak. The floor `make bench` states (docs/design.md section
      // 2.6, "Cost") is one numeric factorisation of this matrix, with its
      // analysis already done as in the run, plus our back-substitutions.
      restore_factorization();
      result.reference_factorize_seconds = median_seconds([&] { factorization.factorize(laplacian.matrix()); });
      const Eigen::MatrixX3d rhs = x;
      result.reference_solve_seconds = median_seconds([&] { return factorization.solve(rhs); });
    }
    result.reference_measure_seconds = median_seconds([&] { return quality.measure(x); });
  }
  result.positions = std::move(x);
  return std::move(result);
}

}  // namespace polycube
