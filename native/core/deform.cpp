#include "core/deform.h"

#include <Eigen/SparseCholesky>
#include <chrono>

#include "core/axis.h"
#include "core/check_input.h"
#include "core/components.h"
#include "core/cotangent_weights.h"
#include "core/laplacian.h"
#include "core/nearest_labels.h"
#include "core/poisson_rhs.h"
#include "core/triangulate.h"

namespace polycube {
namespace {

// L is singular: each component floats by a translation. A shift of eps on the
// diagonal, with eps * x_i on the right, makes the system definite and is
// exact at fixed points (L x_i = b there, so x_i still solves it); eps is far
// below L's smallest non-zero eigenvalue on any mesh we can hold in memory.
constexpr double kRelativeShift = 1e-8;

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
  if (name == "fixed") return Variant::kFixed;
  if (name == "current") return Variant::kCurrent;
  throw Error("unknown variant '" + name + "': use 'fixed' or 'current'");
}

const char* variant_name(Variant variant) { return variant == Variant::kFixed ? "fixed" : "current"; }

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

  Eigen::MatrixX3d rhs(n, 3), solution(n, 3);
  for (int iteration = 1; iteration <= options.iterations && !result.converged; ++iteration) {
    if (options.variant == Variant::kCurrent) rebuild(x);
    rhs = poisson_rhs(x, triangles, weights, triangle_labels) + shift * x;
    result.seconds.rotations += phase.lap();
    solution = factorization.solve(rhs);
    if (!solution.allFinite())
      throw Error("the linear solve gave non-finite positions at iteration " + std::to_string(iteration));
    const Eigen::MatrixX3d drift = component_centroids(solution, parts) - centroids;
    for (int v = 0; v < n; ++v) {
      const int c = parts.of_vertex[v];
      x.row(v) = c < 0 ? Eigen::RowVector3d(mesh.vertices.row(v)) : Eigen::RowVector3d(solution.row(v) - drift.row(c));
    }
    result.seconds.solve += phase.lap();

    result.figures = quality.measure(x);
    result.iterations = iteration;
    result.converged = result.figures.normal_deviation_max_deg < options.tolerance_deg;
    result.seconds.measure += phase.lap();
    if (callback && !callback(iteration, x, result.figures)) {
      result.stopped = true;
      break;
    }
    phase.lap();  // time spent in the callback belongs to the caller
  }
  result.positions = std::move(x);
  result.seconds.total = total.lap();
  return result;
}

}  // namespace polycube
