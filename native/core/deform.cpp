#include "core/deform.h"

#include <Eigen/SparseCholesky>
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>

#include "core/axis.h"
#include "core/check_input.h"
#include "core/components.h"
#include "core/cotangent_weights.h"
#include "core/face_states.h"
#include "core/fitted_rotations.h"
#include "core/laplacian.h"
#include "core/nearest_labels.h"
#include "core/poisson_rhs.h"
#include "core/rotated_edges_rhs.h"
#include "core/triangulate.h"

namespace polycube {
namespace {

// L is singular: each component floats by a translation. A shift of eps on the
// diagonal, with eps * x_i on the right, makes the system definite and is
// exact at fixed points (L x_i = b there, so x_i still solves it); eps is far
// below L's smallest non-zero eigenvalue on any mesh we can hold in memory.
constexpr double kRelativeShift = 1e-8;

// The robust variant's step control and phase switch (see deform.h).
constexpr int kMaxHalvings = 6;
constexpr int kMaxFreezeRounds = 20;
constexpr int kMaxFitIterations = 30;
constexpr double kFitStepTolerance = 1e-3;

using Factorization = Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower, Eigen::AMDOrdering<int>>;

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

// The centroid of each component, so the solve can be put back in place.
Eigen::MatrixX3d component_centroids(const Vertices& x, const Components& components) {
  Eigen::MatrixX3d sum = Eigen::MatrixX3d::Zero(components.count, 3);
  Eigen::VectorXd count = Eigen::VectorXd::Zero(components.count);
  for (Eigen::Index v = 0; v < x.rows(); ++v) {
    const int c = components.of_vertex[v];
    if (c < 0) continue;
    sum.row(c) += x.row(v);
    count[c] += 1.0;
  }
  for (int c = 0; c < components.count; ++c) sum.row(c) /= count[c];
  return sum;
}

void factorize(Factorization& factorization, const SparseMatrix& matrix) {
  factorization.factorize(matrix);
  if (factorization.info() != Eigen::Success)
    throw Error("the sparse factorisation of the Laplacian failed (the mesh may be badly degenerate)");
}

}  // namespace

Variant parse_variant(const std::string& name) {
  if (name == "robust") return Variant::kRobust;
  if (name == "fixed") return Variant::kFixed;
  if (name == "current") return Variant::kCurrent;
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

DeformResult deform(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                    const IterationCallback& callback) {
  check_input(mesh, &labels);
  if (options.iterations < 0) throw Error("the iteration limit must be 0 or more");
  if (!(options.tolerance_deg >= 0.0)) throw Error("the tolerance must be 0 or more degrees");

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
  const QualityMeasure quality(mesh.vertices, triangles, triangle_labels);
  Vertices x = mesh.vertices;
  result.figures = quality.measure(x);
  result.converged = result.figures.normal_deviation_max_deg < options.tolerance_deg;
  result.seconds.measure += phase.lap();

  Laplacian laplacian(n, triangles);
  Factorization factorization;
  factorization.analyzePattern(laplacian.matrix());
  Eigen::MatrixX3d solution(n, 3);
  // Solves L y = rhs and puts every component's centroid back where it was.
  auto solve = [&](const Eigen::MatrixX3d& rhs, int iteration) {
    solution = factorization.solve(rhs);
    if (!solution.allFinite())
      throw Error("the linear solve gave non-finite positions at iteration " + std::to_string(iteration));
    const Eigen::MatrixX3d drift = component_centroids(solution, parts) - centroids;
    Vertices y(n, 3);
    for (int v = 0; v < n; ++v) {
      const int c = parts.of_vertex[v];
      y.row(v) = c < 0 ? Eigen::RowVector3d(mesh.vertices.row(v)) : Eigen::RowVector3d(solution.row(v) - drift.row(c));
    }
    return y;
  };
  // Measures, reports to the callback; false when the run must stop.
  auto finish_iteration = [&](int iteration) {
    result.figures = quality.measure(x);
    result.iterations = iteration;
    result.converged = result.figures.normal_deviation_max_deg < options.tolerance_deg;
    result.seconds.measure += phase.lap();
    if (callback && !callback(iteration, x, result.figures)) {
      result.stopped = true;
      return false;
    }
    phase.lap();  // time spent in the callback belongs to the caller
    return !result.converged;
  };

  if (options.variant == Variant::kRobust) {
    // Positive weights: with negative cotangents L is indefinite and the
    // global step can fold triangles on its own (bone: 16% of the input's
    // corners are obtuse). Clamping at zero keeps L positive semidefinite.
    CotangentWeights weights = cotangent_weights(mesh.vertices, triangles).cwiseMax(0.0);
    double shift = laplacian.assemble(weights, kRelativeShift);
    result.seconds.assemble += phase.lap();
    if (!result.converged) factorize(factorization, laplacian.matrix());
    result.seconds.factorize += phase.lap();

    const FaceStateMeasure state_measure(mesh.vertices, triangles, triangle_labels);
    FaceStates state = state_measure.measure(x);
    const double diagonal = (mesh.vertices.colwise().maxCoeff() - mesh.vertices.colwise().minCoeff()).norm();
    bool exact = false;
    int fit_iterations = 0;
    for (int iteration = 1; iteration <= options.iterations && !result.converged; ++iteration) {
      Eigen::MatrixX3d rhs;
      if (!exact) {
        const Rotations rotations = fitted_rotations(mesh.vertices, x, triangles, weights, triangle_labels);
        rhs = rotated_edges_rhs(mesh.vertices, triangles, weights, rotations) + shift * x;
        ++fit_iterations;
      } else {
        if (std::getenv("PCCUR")) {
          weights = cotangent_weights(x, triangles).cwiseMax(0.0);
          shift = laplacian.assemble(weights, kRelativeShift);
          factorize(factorization, laplacian.matrix());
        }
        rhs = poisson_rhs(x, triangles, weights, triangle_labels) + shift * x;
      }
      result.seconds.rotations += phase.lap();
      const Vertices target = solve(rhs, iteration);
      result.seconds.solve += phase.lap();
      // Step control: move every vertex the whole way unless that folds a
      // triangle that was not folded; then shorten the steps of that
      // triangle's corners only, so a few faces that want to fold do not hold
      // the rest of the mesh back.
      std::vector<double> alpha(n, 1.0);
      Vertices candidate(n, 3);
      FaceStates candidate_state;
      int rounds = 0, limited = 0;
      for (;; ++rounds) {
        for (int v = 0; v < n; ++v) candidate.row(v) = x.row(v) + alpha[v] * (target.row(v) - x.row(v));
        candidate_state = state_measure.measure(candidate);
        bool folds = false;
        for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
          if (!candidate_state.flipped[t] || state.flipped[t]) continue;
          folds = true;
          for (int k = 0; k < 3; ++k) {
            double& a = alpha[triangles(t, k)];
            a = rounds < kMaxHalvings ? 0.5 * a : 0.0;
          }
        }
        if (!folds) break;
        // A triangle whose corners all stand still can still change class
        // when the global scale s moves the collapse threshold; give up on
        // the step rather than loop.
        if (rounds == kMaxHalvings + kMaxFreezeRounds) {
          std::fill(alpha.begin(), alpha.end(), 0.0);
          candidate = x;
          candidate_state = state;
          break;
        }
      }
      for (int v = 0; v < n; ++v) limited += alpha[v] < 1.0;
      {
        const Eigen::MatrixX3d drift = component_centroids(candidate, parts) - centroids;
        for (int v = 0; v < n; ++v)
          if (parts.of_vertex[v] >= 0) candidate.row(v) -= drift.row(parts.of_vertex[v]);
      }
      const double step = (candidate - x).rowwise().norm().maxCoeff() / diagonal;
      const bool accepted = limited < n;
      x = std::move(candidate);
      state = std::move(candidate_state);
      const double alpha_min = *std::min_element(alpha.begin(), alpha.end());
      if (std::getenv("PCDEBUG"))
        std::fprintf(stderr, "it %d exact=%d alpha_min=%g limited=%d step=%g max=%g flipped=%d\n", iteration, exact,
                     alpha_min, limited, step, state.max_deviation_deg, state.flipped_count);
      if (!exact && (step < kFitStepTolerance || fit_iterations >= kMaxFitIterations || !accepted)) exact = true;
      if (!finish_iteration(iteration)) break;
    }
  } else {
    CotangentWeights weights;
    double shift = 0.0;
    auto rebuild = [&](const Vertices& from) {
      weights = cotangent_weights(from, triangles);
      shift = laplacian.assemble(weights, kRelativeShift);
      result.seconds.assemble += phase.lap();
      factorize(factorization, laplacian.matrix());
      result.seconds.factorize += phase.lap();
    };
    if (options.variant == Variant::kFixed && !result.converged) rebuild(mesh.vertices);
    else result.seconds.assemble += phase.lap();

    for (int iteration = 1; iteration <= options.iterations && !result.converged; ++iteration) {
      if (options.variant == Variant::kCurrent) rebuild(x);
      const Eigen::MatrixX3d rhs = poisson_rhs(x, triangles, weights, triangle_labels) + shift * x;
      result.seconds.rotations += phase.lap();
      x = solve(rhs, iteration);
      result.seconds.solve += phase.lap();
      if (!finish_iteration(iteration)) break;
    }
  }

  // The faces that did not make it, by polygon id.
  {
    const FaceStates state = FaceStateMeasure(mesh.vertices, triangles, triangle_labels).measure(x);
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
  result.positions = std::move(x);
  result.seconds.total = total.lap();
  return result;
}

}  // namespace polycube
