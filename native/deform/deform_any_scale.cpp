// deform() at any scale: the model moved into the unit box (unit_box.h),
// deformed there, and the positions (of the result and of every iteration
// the callback sees) moved back. The figures are scale-free already. The
// robust variant's second run with collapsed faces relabelled is here too:
// it wraps whole runs.
#include <Eigen/Geometry>
#include <algorithm>
#include <memory>
#include <utility>

#include "deform/coarse_to_fine.h"
#include "deform/deform.h"
#include "deform/deformation.h"
#include "deform/finished_run.h"
#include "deform/keep_opposites_apart.h"
#include "deform/polish_stage.h"
#include "deform/quality.h"
#include "deform/recut_collapsed_faces.h"
#include "deform/relabel_collapsed_faces.h"
#include "deform/robust_run.h"
#include "deform/untangle_flat_charts.h"
#include "labels/axis.h"
#include "labels/keep_valid_moves.h"
#include "labels/label_energy.h"
#include "labels/repair_charts.h"
#include "labels/validate_labels.h"
#include "labels/violation_score.h"
#include "mesh/check_input.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"

namespace polycube {
namespace {

// The repair after stage 8's relabelling: a label barred from a face costs
// this much more (more than any fidelity, less than overflow), and the
// repair gets as many moves as the labeller's.
constexpr double kBarred = 1e6;
constexpr int kRepairMoves = 200;
// Stage 8 runs again while a run is kept, at most this many times: each
// round's polycube shows the collapsed faces the last relabelling left.
// The moves that break nothing take small steps: the held-out hand took
// seven runs to 0.50% of its area collapsed, nine to 0.35%.
constexpr int kRerunRounds = 10;
// ... and while they pay: once less than kMarginArea of the area and
// kMarginFaces of the triangles are collapsed (half the goal of
// docs/design.md section 4: 0.5% of the area, 1% of the faces), a kept run
// that lowered the collapsed area by less than kRerunGain ends them. Each
// further run costs a whole run, and from there on they gain little:
// bunny00 0.101% -> 0.061% -> 0.049%, then a run not kept (7 s of its 23);
// armadillo 0.72% -> 0.29% -> 0.25%, then one not kept. Above that margin
// they go on for any gain (the dragon: 0.50% -> 0.47% -> ... -> 0.41%).
constexpr double kMarginArea = 0.0025;
constexpr double kMarginFaces = 0.005;
constexpr double kRerunGain = 0.25;

// Whether `figures` collapse less than the margins above, of `triangles`.
bool within_margins(const Figures& figures, long triangles) {
  return figures.collapsed_area < kMarginArea &&
         figures.collapsed_faces < kMarginFaces * static_cast<double>(triangles);
}
// After the coarse route (coarse_to_fine.h), on a mesh of this many
// triangles or more, no further run is made once the result is within the
// margins, whatever it would gain: the coarse run's own further runs did
// the relabelling at 50,000 triangles, and at full resolution each costs 3
// to 6 s for hundredths of a percent of the area (armadillo refined 16
// times: six runs, 0.074% -> 0.0011%, 15 of its 59 s; bunny00 refined 16
// times: three, 0.022% -> 0.0024%, 13 of 62 s). Below it a further run
// costs about a second, and they go on as above (armadillo refined 4 times:
// 0.134% -> 0.051% for 1 s of its 32).
constexpr long kCostlyRerunsFrom = 500'000;
// Once the result is good (the goal of docs/design.md section 4: twice the
// margins above), a kept run that lowered the collapsed area by less than
// this share crawls: the boundary moved face by face lands on faces that
// collapse about as much (mannequin-devil: six such runs, 0.312% -> 0.307%,
// the area error 0.41 -> 0.51, its largest area ratio 203 -> 1918, before a
// round that kept nothing cut its collapsed faces again: 0.02%). The next
// round cuts them again first (recut_collapsed_faces.h), then tries the
// neighbours' labels. Above the goal a crawl is often followed by large
// gains (the camel 1.076% -> 1.070% -> 0.956%), and the cut tried there
// cost runs for nothing or, ending stage 8, lost those gains.
constexpr double kRerunCrawl = 0.02;
// Stage 8 once stalled: the first round whose relabelling is not kept ended
// stage 8 before the collapsed faces were also cut again
// (recut_collapsed_faces.h). From that round on, the further runs may number
// at most this share of the runs made until then (the first run included),
// so a model's deformation costs at most about this much more than it did.
constexpr double kStalledRunsShare = 0.5;
// ... and a run is then kept only when its edge and area errors are within
// this factor of the result's: a new cut can open collapsed faces by
// stretching others (double-torus-example: 7.4% -> 5.7% of its triangles'
// area collapsed, area error 0.48 -> 0.81).
constexpr double kStalledErrorSlack = 1.1;
// ... and its largest area ratio within this factor: no fin (the held-out
// camel: 0.79% -> 0.52% of its area collapsed, but a triangle 238 times
// its area where the largest was 14; with this bound 0.50%, and 14).
constexpr double kStalledRatioSlack = 2.0;

// The further runs stage 8 may still make: unbounded (-1) until a round
// stalls, then kStalledRunsShare of the runs made so far.
struct RerunBudget {
  int runs_left = -1;
  // The stalled bounds (kStalledErrorSlack, kStalledRatioSlack) apply to the
  // cut after a crawl too, which does not start the budget.
  bool bounded = false;
  bool spend() {
    if (runs_left == 0) return false;
    if (runs_left > 0) --runs_left;
    return true;
  }
};
// What the further runs need of the mesh, built once for all of them.
struct RerunMesh {
  explicit RerunMesh(const PolygonMesh& mesh)
      : triangulation(triangulate(mesh.vertices, mesh.faces)),
        adjacency(mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows()))),
        neighbours(face_neighbours(adjacency, mesh.faces.count())),
        edges_of_face(face_edges(adjacency, mesh.faces.count())),
        energy(label_energy(mesh, mesh.vertices, adjacency, kDefaultCompactness)) {}
  Triangulation triangulation;
  MeshAdjacency adjacency;
  std::vector<std::vector<int>> neighbours;
  std::vector<std::vector<int>> edges_of_face;
  LabelEnergy energy;  // the labeller's, for the re-cut and the repair
  // How the further runs from the result untangle (untangle_flat_charts.h).
  NearStart near_start;
};

// Whether `result` comes from a run after the first (a further run or the
// last resort) kept only by untangling its first flat solve, its rounds
// refused (flatten_stage.h).
bool rounds_refused(const DeformResult& result) {
  if (result.second_run_iterations == 0) return false;
  const auto& attempts = result.flatten_attempts;
  const auto kept = std::find_if(attempts.rbegin(), attempts.rend(),
                                 [](const DeformResult::FlattenAttempt& a) { return a.kept; });
  return kept != attempts.rend() && kept->rounds > 0 && kept->untangle_rounds > 0;
}

// A run the caller does not see (its iterations start again from the
// input, and a caller that keeps every iteration, as shape keys, would get a
// run it may not keep); only `stop_requested` (polled by the run itself)
// reaches it. Not converged unless it is an exact polycube with nothing
// turned over and no more edges folded than the input's. What it leaves for a polish goes to `finished`.
DeformResult silent_run(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                        std::unique_ptr<FinishedRun>& finished, const Vertices& near = Vertices(),
                        NearStart near_start = NearStart()) {
  DeformResult run = deform_in_unit_box(mesh, labels, options, IterationCallback{}, finished, near, near_start);
  run.converged = !run.stopped && run.converged && run.figures.flipped_faces == 0 &&
                  run.figures.folded_edges <= run.input_folded_edges;
  return run;
}

// The figures of `positions` against the labels the caller gave, unlabelled
// faces taking their nearest axis.
Figures given_labels_figures(const PolygonMesh& mesh, const Triangulation& triangulation,
                             const std::vector<int>& labels, const Vertices& positions) {
  const std::vector<int> given = filled_labels(mesh, labels);
  std::vector<int> triangle_labels(triangulation.face_of_triangle.size());
  for (size_t t = 0; t < triangle_labels.size(); ++t) triangle_labels[t] = given[triangulation.face_of_triangle[t]];
  return QualityMeasure(mesh.vertices, triangulation.triangles, triangle_labels).measure(positions);
}

// The share of the input's area in collapsed polygons of `positions`: a
// polygon is collapsed (is_collapsed) by its triangles' output area together. On a mesh of
// triangles this is Figures::collapsed_area; on a quad mesh a quad bent to a
// triangle's shape keeps its area, and a run can collapse fewer triangles
// but more quads (Suzanne: 2.72% -> 2.67% of the area in collapsed
// triangles, 0.37% -> 1.00% in collapsed quads).
double collapsed_polygon_area(const PolygonMesh& mesh, const Triangulation& triangulation, const Vertices& positions) {
  const int faces = mesh.faces.count();
  std::vector<double> before(faces, 0.0), after(faces, 0.0);
  double total_before = 0.0, total_after = 0.0;
  for (Eigen::Index t = 0; t < triangulation.triangles.rows(); ++t) {
    const auto area = [&](const Vertices& x) {
      const Eigen::Vector3d a = x.row(triangulation.triangles(t, 0)).transpose();
      const Eigen::Vector3d b = x.row(triangulation.triangles(t, 1)).transpose();
      const Eigen::Vector3d c = x.row(triangulation.triangles(t, 2)).transpose();
      return 0.5 * (b - a).cross(c - a).norm();
    };
    const int f = triangulation.face_of_triangle[t];
    const double in = area(mesh.vertices), out = area(positions);
    before[f] += in, after[f] += out;
    total_before += in, total_after += out;
  }
  if (!(total_before > 0.0)) return 0.0;
  const double scale2 = total_after > 0.0 ? total_after / total_before : 1.0;
  double collapsed = 0.0;
  for (int f = 0; f < faces; ++f)
    if (is_collapsed(after[f], before[f], scale2)) collapsed += before[f];
  return collapsed / total_before;
}

// `faces` joined by `more`, ascending, each once (DeformResult::relabelled_faces).
void add_faces(std::vector<int>& faces, const std::vector<int>& more) {
  faces.insert(faces.end(), more.begin(), more.end());
  std::sort(faces.begin(), faces.end());
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
}

// `again` (a silent run) replaces `result`: to the caller it is one more
// iteration, seen once by the callback, its own iterations counted in
// `second_run_iterations`; its figures against the labels the caller gave.
void keep_as_next_iteration(const PolygonMesh& mesh, const Triangulation& triangulation, const std::vector<int>& labels,
                            const IterationCallback& callback, DeformResult again, DeformResult& result) {
  const int offset = result.iterations;
  add_cost(again, result);
  again.given_labels_figures = given_labels_figures(mesh, triangulation, labels, again.positions);
  again.second_run_iterations = result.second_run_iterations + again.iterations;
  again.iterations = again.kept_iteration = offset + 1;
  if (again.flat_iteration > 0) again.flat_iteration = offset + 1;
  again.unlabelled_faces = result.unlabelled_faces;  // the silent run was given them filled
  again.last_resort = again.last_resort || result.last_resort;
  again.coarse_triangles = result.coarse_triangles;
  again.coarse_iterations = result.coarse_iterations;
  std::vector<DeformResult::FlattenAttempt> attempts = result.flatten_attempts;
  for (DeformResult::FlattenAttempt attempt : again.flatten_attempts) {
    attempt.iteration = offset + 1;
    attempts.push_back(attempt);
  }
  again.flatten_attempts = std::move(attempts);
  result = std::move(again);
  if (callback) callback(result.iterations, result.positions, result.figures);
}

// One run of stage 8 from the input with `moved` (labels that differ from
// the result's on some faces), kept as the next iteration when it is exact,
// fold-free and collapses less area, and once stage 8 has stalled, its edge
// and area errors and largest area ratio within kStalledErrorSlack and
// kStalledRatioSlack of the result's, and no more area in collapsed
// polygons (then the faces it relabelled join
// `relabelled_faces`, and what it leaves for a polish replaces `finished`);
// else only its cost is added to `result`. Returns whether it was kept; not
// run (and not kept) when `budget` is spent.
bool keep_if_better(const PolygonMesh& mesh, const RerunMesh& shared, const std::vector<int>& labels,
                    const DeformOptions& options, const IterationCallback& callback, const std::vector<int>& moved,
                    DeformResult& result, std::unique_ptr<FinishedRun>& finished, RerunBudget& budget) {
  if (!budget.spend()) return false;
  // The result's finished run is not held through another: its set-up and
  // factors would add to that run's peak.
  finished.reset();
  std::unique_ptr<FinishedRun> again_finished;
  // DeformOptions::rerun_from_result: at scale the run starts from the
  // result, its charts moved past the relabelled faces (flatten_near,
  // flatten_stage.h); from the input, each further run untangles a whole
  // first solve again (fandisk refined 64 times: 30 of each further run's
  // 42 s).
  const bool near = options.rerun_from_result && shared.triangulation.triangles.rows() >= kUntangleNewtonFrom;
  DeformOptions run_options = options;
  if (!options.retry_refused_rounds && rounds_refused(result)) run_options.untangle_first_solve = true;
  DeformResult again =
      silent_run(mesh, moved, run_options, again_finished, near ? result.positions : Vertices(), shared.near_start);
  const bool worse_errors = (budget.runs_left >= 0 || budget.bounded) &&
                            (again.figures.edge_error > kStalledErrorSlack * result.figures.edge_error ||
                             again.figures.area_error > kStalledErrorSlack * result.figures.area_error ||
                             again.figures.max_area_ratio > kStalledRatioSlack * result.figures.max_area_ratio ||
                             collapsed_polygon_area(mesh, shared.triangulation, again.positions) >
                                 collapsed_polygon_area(mesh, shared.triangulation, result.positions));
  if (!again.converged || !(again.figures.collapsed_area < result.figures.collapsed_area) || worse_errors) {
    add_cost(result, again);
    return false;
  }
  finished = std::move(again_finished);
  std::vector<int> relabelled = result.relabelled_faces;
  for (size_t f = 0; f < moved.size(); ++f)
    if (moved[f] != result.labels[f]) relabelled.push_back(static_cast<int>(f));
  add_faces(relabelled, again.relabelled_faces);
  again.relabelled_faces = std::move(relabelled);
  keep_as_next_iteration(mesh, shared.triangulation, labels, callback, std::move(again), result);
  return true;
}

// One labeling of stage 8 (`moved`, differing from the result's labels on
// `changed`) tried as further runs: the whole move when it breaks no more
// polycube conditions than the result's labels, else the moves that break
// nothing, then the whole move mended by the labeller's repair. Returns
// whether a run was kept (keep_if_better).
bool try_moves(const PolygonMesh& mesh, const RerunMesh& shared, const std::vector<int>& labels,
               const DeformOptions& options, const IterationCallback& callback, std::vector<int> moved,
               const std::vector<int>& changed, DeformResult& result, std::unique_ptr<FinishedRun>& finished,
               RerunBudget& budget) {
  if (changed.empty()) return false;
  const MeshAdjacency& adjacency = shared.adjacency;
  const int score = violation_score(adjacency, result.labels);
  if (violation_score(adjacency, moved) <= score)
    return keep_if_better(mesh, shared, labels, options, callback, moved, result, finished, budget);
  // Moving boundaries past collapsed faces can break the polycube conditions
  // elsewhere (a corner of four charts). First the moves that break nothing
  // (keep_valid_moves.h): small steps, but they keep the charts the run
  // had (the anchor: 3.05% of its area collapsed, then 0.03%; the turbine
  // 0.50%, then 0.19%).
  int kept = 0;
  const std::vector<int> valid =
      keep_valid_moves(adjacency, shared.edges_of_face, result.labels, moved, changed, &kept);
  if (kept > 0 && keep_if_better(mesh, shared, labels, options, callback, valid, result, finished, budget)) return true;
  // Then the whole move, mended by the labeller's repair, with the faces'
  // old labels barred so it does not undo the move: it relabels more, and
  // gets further where the small steps stall (the held-out hand: 2.27%,
  // then 0.91%). Their opposites are allowed: with them barred too, the
  // armadillo's third further run collapsed more and it ended at 4.2% of
  // its area collapsed; without, at 0.7%.
  LabelEnergy energy = shared.energy;
  for (int f : changed) energy.data(f, result.labels[f]) += kBarred;
  const std::vector<int> repaired = repair_charts(adjacency, energy, std::move(moved), kRepairMoves);
  if (violation_score(adjacency, repaired) > score) return false;
  return keep_if_better(mesh, shared, labels, options, callback, repaired, result, finished, budget);
}

// Stage 8 (docs/design.md section 2.6): an exact polycube that collapsed
// faces is run once more from the input, its collapsed faces relabelled
// (relabel_collapsed_faces.h), and kept when that run is exact, fold-free
// and collapses less area, with no more polycube conditions broken. When
// it is not kept, the collapsed faces are cut again by the labeller's
// energy instead (recut_collapsed_faces.h) and tried the same way, within
// `budget`. After a run that `crawled` (kRerunCrawl) the cut comes first,
// under the stalled bounds, and the neighbours' labels only when it is not
// kept. Returns whether a run was kept. The callback sees a kept run
// once, as the iteration after the last one it saw
// (DeformResult::second_run_iterations counts the further runs' own
// iterations), and the faces relabelled join `relabelled_faces` (and what it
// leaves for a polish replaces `finished`).
bool rerun_collapsed(const PolygonMesh& mesh, const RerunMesh& shared, const std::vector<int>& labels,
                     const DeformOptions& options, const IterationCallback& callback, DeformResult& result,
                     std::unique_ptr<FinishedRun>& finished, RerunBudget& budget, bool crawled) {
  if (result.stopped || !result.converged || result.figures.collapsed_faces == 0 || result.figures.flipped_faces > 0 ||
      (options.stop_requested && options.stop_requested()))
    return false;
  const Triangulation& triangulation = shared.triangulation;
  std::vector<int> triangle_labels(triangulation.face_of_triangle.size());
  for (size_t t = 0; t < triangle_labels.size(); ++t)
    triangle_labels[t] = result.labels[triangulation.face_of_triangle[t]];
  const FaceStates states =
      QualityMeasure(mesh.vertices, triangulation.triangles, triangle_labels).face_states(result.positions);
  std::vector<char> collapsed(mesh.faces.count(), 0);
  for (size_t t = 0; t < states.collapsed.size(); ++t)
    if (states.collapsed[t]) collapsed[triangulation.face_of_triangle[t]] = 1;
  if (crawled) {
    std::vector<int> recut = result.labels;
    const std::vector<int> cut = recut_collapsed_faces(shared.neighbours, shared.energy, collapsed, recut);
    budget.bounded = true;
    const bool kept = try_moves(mesh, shared, labels, options, callback, recut, cut, result, finished, budget);
    budget.bounded = false;
    if (kept) return true;
  }
  std::vector<int> moved = result.labels;
  std::vector<int> changed = relabel_collapsed_faces(shared.neighbours, collapsed, moved);
  if (try_moves(mesh, shared, labels, options, callback, moved, changed, result, finished, budget)) return true;
  if (crawled) return false;  // the cut below was tried first
  // The neighbours' labels did not help (or reached no collapsed face): a
  // thin part the labeller gave one chart has none of the labels its sides
  // need among its neighbours, and a boundary moved face by face can stall
  // where a new cut of the same faces goes on (section 2.6).
  if (options.stop_requested && options.stop_requested()) return false;
  if (budget.runs_left < 0) budget.runs_left = static_cast<int>(kStalledRunsShare * result.stages.set_up.count);
  moved = result.labels;
  changed = recut_collapsed_faces(shared.neighbours, shared.energy, collapsed, moved);
  return try_moves(mesh, shared, labels, options, callback, moved, changed, result, finished, budget);
}

// Whether stage 9 can change anything: the bound it raises refused one of
// the first run's flattenings (collapsing more than the first bound, no more
// than the raised one). A run whose flattenings were refused for folds
// left, or that never flattened, would be run again for nothing, and a run
// costs minutes at a million triangles (bunny00 refined 16 times: every
// attempt refused for turned-over faces with 10% of its area on a line).
bool refused_for_collapse(const DeformResult& run, const DeformOptions& options) {
  return std::any_of(run.flatten_attempts.begin(), run.flatten_attempts.end(),
                     [&options](const DeformResult::FlattenAttempt& a) {
                       return !a.kept && a.collapsed_area > options.max_collapsed_share &&
                              a.collapsed_area <= kLastResortCollapsedShare;
                     });
}

// The polish (polish_stage.h) of an exact result, on the labels it ended
// with: when it keeps a step, one more iteration to the callback. On the
// set-up and flat charts of the run that gave the result (`finished`, when
// that run is at hand), or on its own: the same positions, labels and
// Laplacian either way, so the same polish bit for bit.
void polish(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
            const IterationCallback& callback, DeformResult& result, std::unique_ptr<FinishedRun> finished) {
  Stopwatch clock;
  DeformOptions from_result = options;
  const IterationCallback none;
  std::unique_ptr<Deformation> own;
  std::unique_ptr<RobustRun> run;
  std::unique_ptr<ChartPlanes> factored;
  if (finished) {
    Deformation& d = *finished->deformation;
    d.x = result.positions;
    d.result = DeformResult();
    d.factorization.release();    // restored by conclude() for the reference timings alone
    d.acceptable_x = Vertices();  // the run's fallback, of no use to the polish
    run = std::make_unique<RobustRun>(d, Assembled{});
    factored = std::move(finished->planes);
  } else {
    from_result.start = result.positions;
    own = std::make_unique<Deformation>(mesh, result.labels, from_result, none);
    run = std::make_unique<RobustRun>(*own);
  }
  Deformation& d = run->d;
  d.weights = CotangentWeights();  // assembled into the Laplacian already; the polish's peak is the run's
  int steps = 0;
  // A polish that breaks down (a flat-chart system that cannot be
  // factorised, a solve that is not finite) costs the caller nothing: the
  // run's result stands.
  try {
    steps = polish_stage(*run, std::move(factored));
  } catch (const Error&) {
    steps = 0;
  }
  result.factorizations += d.result.factorizations;
  result.back_substitutions += d.result.back_substitutions;
  StageSeconds& stages = result.stages;
  ++stages.polish.count;
  const double polish_seconds = clock.lap();
  stages.polish.seconds += polish_seconds;
  double measure_seconds = 0.0;
  if (steps > 0) {
    result.polish_steps = steps;
    result.positions = std::move(d.x);
    result.figures = d.result.figures;  // measured by the polish
    result.given_labels_figures = result.relabelled_faces.empty()
                                      ? result.figures
                                      : given_labels_figures(mesh, d.triangulation, labels, result.positions);
    result.iterations = result.kept_iteration = result.iterations + 1;
    ++stages.measure.count;
    measure_seconds = clock.lap();
    stages.measure.seconds += measure_seconds;
  }
  result.seconds.total += polish_seconds + measure_seconds;
  if (steps > 0 && callback) callback(result.iterations, result.positions, result.figures);
}

}  // namespace

IterationCallback numbered_from(const IterationCallback& callback, int offset) {
  if (!callback) return {};
  return [callback, offset](int iteration, const Vertices& positions, const Figures& figures) {
    return callback(offset + iteration, positions, figures);
  };
}

// A silent run's time, solves and stages count whether it is kept or not:
// the report's stages then still add up to its total, and bench's floor
// counts every back-substitution.
void add_cost(DeformResult& into, const DeformResult& from) {
  PhaseSeconds& t = into.seconds;
  const PhaseSeconds& u = from.seconds;
  t.total += u.total, t.assemble += u.assemble, t.factorize += u.factorize, t.rotations += u.rotations;
  t.solve += u.solve, t.measure += u.measure;
  into.factorizations += from.factorizations;
  if (into.solver.empty()) into.solver = from.solver;
  into.back_substitutions += from.back_substitutions;
  StageSeconds& a = into.stages;
  const StageSeconds& b = from.stages;
  for (auto [x, y] : {std::pair{&a.set_up, &b.set_up},
                      {&a.fit, &b.fit},
                      {&a.continuous, &b.continuous},
                      {&a.relax, &b.relax},
                      {&a.flatten, &b.flatten},
                      {&a.untangle, &b.untangle},
                      {&a.measure, &b.measure},
                      {&a.polish, &b.polish}}) {
    x->count += y->count;
    x->seconds += y->seconds;
  }
  a.current_steps += b.current_steps;
}

DeformResult deform(const PolygonMesh& input, const std::vector<int>& labels, const DeformOptions& options,
                    const IterationCallback& callback) {
  check_input(input, &labels);
  const UnitBoxMesh unit(input);
  const PolygonMesh& mesh = unit.mesh();
  IterationCallback unit_callback = callback;
  if (callback && !unit.box().identity())
    unit_callback = [&](int iteration, const Vertices& positions, const Figures& figures) {
      return callback(iteration, unit.box().from_unit(positions, mesh.vertices, input.vertices), figures);
    };
  DeformOptions unit_options = options;
  if (options.start.size() > 0) unit_options.start = unit.box().to_unit(options.start);
  // What the run that gave `result` leaves for its polish, while at hand.
  std::unique_ptr<FinishedRun> finished;
  long triangles = 0;
  for (int f = 0; f < mesh.faces.count(); ++f) triangles += std::max(mesh.faces.size(f) - 2, 0);
  const bool route = coarse_route_applies(unit_options, triangles);
  // The mesh's own run goes as far as its first flattening attempt to show
  // whether the labels flatten without help (coarse_to_fine.h). Labels that
  // break the polycube conditions (violation_score.h) never did at the
  // route's scale, and that attempt is a sixth of the whole run (bunny00
  // refined 16 times, nearest labels: 7.6 of 49 s): they go to the route
  // at once (docs/design.md section 2.8).
  Stopwatch clock;
  const bool at_once = route && violation_score(mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows())),
                                                filled_labels(mesh, labels)) > 0;
  const double check_seconds = route ? clock.lap() : 0.0;
  DeformResult result;
  if (at_once)
    result.handed_over = true;
  else
    result = deform_in_unit_box(mesh, labels, unit_options, unit_callback, finished, Vertices(), NearStart(), route);
  // The check is set-up, counted like the rest (a quarter of a second at a
  // million triangles, B0 refined 64 times included).
  result.seconds.total += check_seconds;
  result.stages.set_up.seconds += check_seconds;
  bool coarse = false;
  if (result.handed_over) {
    const DeformResult handed_over = std::move(result);
    finished.reset();
    coarse = coarse_to_fine(mesh, labels, unit_options, unit_callback, handed_over, result, finished);
    if (coarse) {
      result.given_labels_figures =
          result.relabelled_faces.empty()
              ? result.figures
              : given_labels_figures(mesh, triangulate(mesh.vertices, mesh.faces), labels, result.positions);
    } else {
      // The route not taken: the mesh deformed itself after all, what the
      // route spent (the handed-over run included) counted in.
      // Its iterations follow those the callback saw already.
      const DeformResult spent = std::move(result);
      const int offset = spent.iterations;
      result = deform_in_unit_box(mesh, labels, unit_options, numbered_from(unit_callback, offset), finished);
      add_cost(result, spent);
      result.iterations += offset;
      result.kept_iteration += offset;
      result.coarse_iterations = offset;
      if (result.flat_iteration > 0) result.flat_iteration += offset;
    }
  }
  const bool robust = options.variant == Variant::kRobust;
  std::unique_ptr<RerunMesh> shared;
  // The coarse run made its own last resort and further runs.
  if (robust && !coarse && options.last_resort && !result.converged && !result.stopped &&
      unit_options.max_collapsed_share < kLastResortCollapsedShare && refused_for_collapse(result, unit_options) &&
      !(options.stop_requested && options.stop_requested())) {
    DeformOptions last_resort = unit_options;
    last_resort.max_collapsed_share = kLastResortCollapsedShare;
    finished.reset();  // not held through another run
    std::unique_ptr<FinishedRun> again_finished;
    DeformResult again = silent_run(mesh, labels, last_resort, again_finished);
    again.last_resort = true;  // and the further runs below keep saying so
    if (again.converged) {
      finished = std::move(again_finished);
      shared = std::make_unique<RerunMesh>(mesh);
      keep_as_next_iteration(mesh, shared->triangulation, labels, unit_callback, std::move(again), result);
      unit_options = last_resort;  // the further runs below flatten the same way
    } else {
      add_cost(result, again);
    }
  }
  // Still no exact polycube: where the labels put opposite labels back to
  // back across an edge the input does not fold, every exact polycube folds
  // it or collapses a face there, and the untangled attempts fold it
  // (keep_opposites_apart.h). One more run with those faces parted; models
  // whose run is exact are not touched (docs/design.md section 2.6, stage 9).
  if (robust && !coarse && options.last_resort && !result.converged && !result.stopped &&
      !(options.stop_requested && options.stop_requested())) {
    if (!shared) shared = std::make_unique<RerunMesh>(mesh);
    std::vector<int> parted = filled_labels(mesh, labels);
    const std::vector<int> changed = part_opposite_neighbours(mesh, shared->adjacency, shared->neighbours, parted);
    if (!changed.empty()) {
      finished.reset();
      std::unique_ptr<FinishedRun> again_finished;
      DeformResult again = silent_run(mesh, parted, unit_options, again_finished);
      if (again.converged) {
        finished = std::move(again_finished);
        add_faces(again.relabelled_faces, changed);
        keep_as_next_iteration(mesh, shared->triangulation, labels, unit_callback, std::move(again), result);
      } else {
        add_cost(result, again);
      }
    }
  }
  // After the coarse route (coarse_to_fine.h) the further runs start from
  // the result and untangle around the faces they relabel alone, as the
  // route's own fine run does: from the input each would be the whole run
  // the route saved.
  if (coarse) {
    unit_options.rerun_from_result = true;
    unit_options.coarse_triangles = 0;
    // Labels that flattened in the coarse run's last resort flatten the
    // same way at full resolution.
    if (result.last_resort) unit_options.max_collapsed_share = kLastResortCollapsedShare;
  }
  const bool costly_reruns = coarse && triangles >= kCostlyRerunsFrom;
  if (robust && options.relabel_collapsed && result.converged && result.figures.collapsed_faces > 0 &&
      !(costly_reruns && within_margins(result.figures, triangles))) {
    if (!shared) shared = std::make_unique<RerunMesh>(mesh);
    if (coarse) shared->near_start = {UntangleStart::local_only, true};
    RerunBudget budget;
    bool crawled = false;
    for (int round = 0; round < kRerunRounds; ++round) {
      const double before = result.figures.collapsed_area;
      if (!rerun_collapsed(mesh, *shared, labels, unit_options, unit_callback, result, finished, budget, crawled))
        break;
      const Figures& now = result.figures;
      if (within_margins(now, triangles) && (costly_reruns || now.collapsed_area > (1.0 - kRerunGain) * before))
        break;
      const bool good = now.collapsed_area < 2.0 * kMarginArea && now.collapsed_faces < 2.0 * kMarginFaces * triangles;
      crawled = good && now.collapsed_area > (1.0 - kRerunCrawl) * before;
    }
  }
  // The polish is one more iteration: within the limit, like the others.
  if (robust && options.polish && result.converged && !result.stopped && result.figures.flipped_faces == 0 &&
      result.iterations - result.coarse_iterations < options.iterations &&
      !(options.stop_requested && options.stop_requested()))
    polish(mesh, labels, unit_options, unit_callback, result, std::move(finished));
  result.positions = unit.box().from_unit(result.positions, mesh.vertices, input.vertices);
  // The report never contradicts itself: a run that leaves faces above the
  // tolerance or folded is not converged, whatever the figures' rounding said.
  if (!result.unconverged_faces.empty() || !result.flipped_faces.empty() ||
      !(result.figures.normal_deviation_max_deg < options.tolerance_deg))
    result.converged = false;
  return result;
}

}  // namespace polycube
