#include "deform/coarse_to_fine.h"

#include <algorithm>
#include <array>
#include <utility>

#include "deform/deformation.h"
#include "deform/finished_run.h"
#include "deform/keep_opposites_apart.h"
#include "deform/untangle_flat_charts.h"
#include "labels/axis.h"
#include "labels/validate_labels.h"
#include "mesh/decimate_charts.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"

namespace polycube {
namespace {

// The fine faces' labels after the coarse run: each keeps its own, but where
// the coarse run relabelled the coarse triangles that hold most of its
// corners (of its own chart's label: a corner on a seam may be homed in the
// neighbouring chart's), it takes their new label.
std::vector<int> carried_labels(const Triangulation& triangulation, const std::vector<int>& own,
                                const Decimation& decimation, const std::vector<int>& coarse_labels) {
  std::vector<int> fine = own;
  const Triangles& triangles = triangulation.triangles;
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    const int face = triangulation.face_of_triangle[t];
    const int label = own[face];
    std::array<int, 3> votes{};
    std::array<int, 3> to{};
    int distinct = 0;
    for (int k = 0; k < 3; ++k) {
      const int c = decimation.home[triangles(t, k)];
      if (decimation.labels[c] != label || coarse_labels[c] == label) continue;
      int i = 0;
      while (i < distinct && to[i] != coarse_labels[c]) ++i;
      if (i == distinct) to[distinct++] = coarse_labels[c];
      ++votes[i];
    }
    for (int i = 0; i < distinct; ++i)
      if (votes[i] >= 2) fine[face] = to[i];
  }
  return fine;
}

// The coarse run's relabelled charts, drawn on the fine faces, end in teeth:
// faces whose three corners all lie on the boundary with one other chart,
// two of their neighbours across it. In the polycube that boundary is a
// line, so a tooth is collapsed onto it (bunny00 refined 16 times: 10,550
// faces, 0.64% of its area). Each tooth takes that other chart's label (its
// boundary one edge shorter, so this ends), among the faces the relabelling
// changed and their neighbours.
void without_teeth(const PolygonMesh& mesh, const std::vector<std::vector<int>>& neighbours,
                   const std::vector<int>& given, std::vector<int>& labels) {
  const int faces = mesh.faces.count();
  std::vector<int> queue;
  std::vector<char> queued(faces, 0);
  const auto push = [&](int f) {
    if (!queued[f]) queue.push_back(f);
    queued[f] = 1;
  };
  for (int f = 0; f < faces; ++f)
    if (labels[f] != given[f]) {
      push(f);
      for (int g : neighbours[f]) push(g);
    }
  while (!queue.empty()) {
    const int f = queue.back();
    queue.pop_back();
    queued[f] = 0;
    if (mesh.faces.size(f) != 3) continue;
    // Two neighbours across one boundary (a triangle has three).
    int to = kUnlabelled;
    for (int g : neighbours[f]) {
      if (labels[g] == labels[f]) continue;
      const auto same = std::count_if(neighbours[f].begin(), neighbours[f].end(),
                                      [&](int h) { return labels[h] == labels[g]; });
      if (same >= 2) to = labels[g];
    }
    if (to == kUnlabelled) continue;
    labels[f] = to;
    for (int g : neighbours[f]) push(g);
  }
}

// The mesh decimated with the charts of `labels` (per polygon face) kept.
Decimation decimate_along(const Vertices& vertices, const Triangulation& triangulation, const std::vector<int>& labels,
                          int target) {
  std::vector<int> triangle_labels(triangulation.face_of_triangle.size());
  for (size_t t = 0; t < triangle_labels.size(); ++t) triangle_labels[t] = labels[triangulation.face_of_triangle[t]];
  return decimate_charts(vertices, triangulation.triangles, triangle_labels, target);
}

PolygonMesh coarse_mesh(const Vertices& vertices, const Decimation& decimation) {
  PolygonMesh coarse;
  coarse.vertices.resize(static_cast<Eigen::Index>(decimation.kept.size()), 3);
  for (size_t i = 0; i < decimation.kept.size(); ++i) coarse.vertices.row(i) = vertices.row(decimation.kept[i]);
  for (Eigen::Index t = 0; t < decimation.triangles.rows(); ++t)
    coarse.faces.add({decimation.triangles(t, 0), decimation.triangles(t, 1), decimation.triangles(t, 2)});
  return coarse;
}

}  // namespace

bool coarse_route_applies(const DeformOptions& options, Eigen::Index triangles) {
  // A start of the caller's (the labeller's straightened shape) is a fine
  // mesh's shape the coarse run would not see.
  return options.variant == Variant::kRobust && options.coarse_triangles > 0 && options.start.size() == 0 &&
         options.iterations > 0 && static_cast<double>(triangles) >= kCoarseFromRatio * options.coarse_triangles;
}

bool coarse_to_fine(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                    const IterationCallback& callback, const DeformResult& handed_over, DeformResult& result,
                    std::unique_ptr<FinishedRun>& finished) {
  Stopwatch clock;
  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  const Eigen::Index fine_triangles = triangulation.triangles.rows();
  std::vector<int> fine = filled_labels(mesh, labels);
  const std::vector<int> given = fine;
  Decimation decimation = decimate_along(mesh.vertices, triangulation, fine, options.coarse_triangles);
  const bool coarse_enough =
      kCoarseFromRatio * static_cast<double>(decimation.triangles.rows()) <= static_cast<double>(fine_triangles);
  double own_seconds = clock.lap();  // decimating and carrying

  DeformOptions coarse_options = options;
  coarse_options.coarse_triangles = 0;
  // Its stage 8 looks for labels the fine run flattens: a further run after
  // one whose rounds were refused goes to the untangling at once.
  coarse_options.retry_refused_rounds = false;
  coarse_options.untangle_again_above = kCoarseUntangleAgainAbove;
  DeformResult spent_coarse;  // the cost of the runs made: the handed-over one, the coarse one
  add_cost(spent_coarse, handed_over);
  int offset = handed_over.iterations;  // their iterations
  // What a route not taken cost, for the caller's report.
  const auto spent = [&](const DeformResult* fine_run) {
    result = DeformResult();
    add_cost(result, spent_coarse);
    if (fine_run) add_cost(result, *fine_run);
    result.stages.set_up.seconds += own_seconds;
    result.seconds.total += own_seconds;
    result.iterations = offset;
    return false;
  };
  if (!coarse_enough) return spent(nullptr);
  const IterationCallback numbered = numbered_from(callback, offset);
  IterationCallback coarse_callback;
  if (numbered)
    coarse_callback = [&](int iteration, const Vertices& positions, const Figures& figures) {
      return numbered(iteration, carry_to_fine(decimation, positions), figures);
    };
  const DeformResult coarse_result =
      deform(coarse_mesh(mesh.vertices, decimation), decimation.labels, coarse_options, coarse_callback);
  add_cost(spent_coarse, coarse_result);
  offset += coarse_result.iterations;
  if (!coarse_result.converged || coarse_result.stopped) return spent(nullptr);
  if (!coarse_result.relabelled_faces.empty()) {
    clock.lap();
    fine = carried_labels(triangulation, fine, decimation, coarse_result.labels);
    const std::vector<std::vector<int>> neighbours = face_neighbours(
        mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows())), mesh.faces.count());
    without_teeth(mesh, neighbours, given, fine);
    keep_opposites_apart(mesh, neighbours, given, fine);
    own_seconds += clock.lap();
  }
  clock.lap();
  const Vertices near = carry_to_fine(decimation, coarse_result.positions);
  own_seconds += clock.lap();
  std::unique_ptr<FinishedRun> fine_finished;
  // Labels that flatten only in the last resort (their coarse polycube
  // collapses more than 12% of the area) flatten the same way here: the
  // carried polycube collapses what the coarse one did, and the fine run's
  // relaxation reopens what the finer mesh leaves room for, stage 8's
  // further runs the rest (armadillo refined 16 times, nearest labels:
  // 0.0011% collapsed at the end, where its own run reached 15.3%).
  DeformOptions fine_options = options;
  if (coarse_result.last_resort) fine_options.max_collapsed_share = kLastResortCollapsedShare;
  DeformResult fine_result = deform_in_unit_box(mesh, fine, fine_options, numbered_from(callback, offset),
                                                fine_finished, near, {UntangleStart::local_only, true});
  // Not exact, or exact only by running from the input as a whole run would:
  // the caller's run does better than this one, whose time is then lost.
  if (!fine_result.converged || fine_result.stopped || fine_result.figures.flipped_faces > 0 ||
      fine_result.figures.folded_edges > fine_result.input_folded_edges || fine_result.flat_iteration != 1)
    return spent(&fine_result);
  fine_result.iterations += offset;
  fine_result.kept_iteration += offset;
  fine_result.flat_iteration += offset;
  add_cost(fine_result, spent_coarse);
  fine_result.stages.set_up.seconds += own_seconds;
  fine_result.seconds.total += own_seconds;
  fine_result.coarse_triangles = static_cast<int>(decimation.triangles.rows());
  fine_result.coarse_iterations = offset;
  fine_result.last_resort = coarse_result.last_resort;
  fine_result.second_run_iterations = coarse_result.second_run_iterations;
  // Faces the coarse runs relabelled, and those the fine run did.
  std::vector<int>& relabelled = fine_result.relabelled_faces;
  for (size_t f = 0; f < fine.size(); ++f)
    if (fine[f] != given[f]) relabelled.push_back(static_cast<int>(f));
  std::sort(relabelled.begin(), relabelled.end());
  relabelled.erase(std::unique(relabelled.begin(), relabelled.end()), relabelled.end());
  result = std::move(fine_result);
  finished = std::move(fine_finished);
  return true;
}

}  // namespace polycube
