// What every variant of deform() (deform.h) builds once and then iterates on:
// the triangulated mesh and its labels, the input's Laplacian and its
// factorisation, the measurement of the figures, the current positions and
// the result being filled. The stages (paper_iteration.h, robust_run.h) are
// functions over this one struct, libigl-style: what is paid once is here,
// what is paid per iteration is in them.
//
// Inputs of the constructor: a mesh already in the unit box that passed
// check_input, its labels per polygon face (-1..5), the options and, for a
// robust run, an exact polycube to flatten from first (`near`, may be
// empty). It fills unlabelled faces with their nearest axis, measures the
// input (and the start shape, if any) and analyses the Laplacian's pattern,
// unless the run starts near a polycube: then the input's Laplacian is
// analysed and factorised only if the run needs it (flatten_near refused,
// flatten_stage.h). It does not assemble or factorise.
#pragma once

#include <chrono>
#include <future>
#include <vector>

#include "deform/deform.h"
#include "deform/quality.h"
#include "deform/untangle_flat_charts.h"
#include "linear_algebra/cotangent_weights.h"
#include "linear_algebra/laplacian.h"
#include "linear_algebra/sparse_cholesky.h"
#include "mesh/components.h"
#include "mesh/triangulate.h"

namespace polycube {

// L is singular: each component floats by a translation. A shift of eps on the
// diagonal, with eps * x_i on the right, makes the system definite and is
// exact at fixed points (L x_i = b there, so x_i still solves it); eps is far
// below L's smallest non-zero eigenvalue on any mesh we can hold in memory.
constexpr double kRelativeShift = 1e-8;

class Stopwatch {
 public:
  // Seconds since the last lap (or the construction).
  double lap() {
    const auto now = std::chrono::steady_clock::now();
    const double seconds = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return seconds;
  }

 private:
  std::chrono::steady_clock::time_point last_ = std::chrono::steady_clock::now();
};

// Charges the time from its construction to its destruction to a stage of
// its own (StageSeconds: flatten, untangle) and sets it apart from the
// iteration it happens in, less what timers inside it charged to theirs.
class StageTimer {
 public:
  StageTimer(StageCost& cost, double& set_apart) : cost_(cost), set_apart_(set_apart), before_(set_apart) {
    ++cost_.count;
  }
  ~StageTimer() {
    const double seconds = clock_.lap() - (set_apart_ - before_);
    cost_.seconds += seconds;
    set_apart_ += seconds;
  }
  StageTimer(const StageTimer&) = delete;
  StageTimer& operator=(const StageTimer&) = delete;

 private:
  StageCost& cost_;
  double& set_apart_;
  const double before_;
  Stopwatch clock_;
};

// How a run given an exact polycube of nearly its labels starts from it
// (Deformation::near, flatten_near in flatten_stage.h).
struct NearStart {
  // How the untangling starts (untangle_flat_charts.h): stage 8's further
  // runs finish with a global round, a coarse polycube carried back
  // (coarse_to_fine.h) does not.
  UntangleStart untangle = UntangleStart::local_then_global;
  // A refused flatten_near ends the run there, not converged, instead of
  // going on from the input: after the coarse route, a run from the input
  // at full resolution is the whole cost the route saves (armadillo refined
  // 16 times: a further run refused near the result went on for minutes).
  bool or_nothing = false;
};

// Below the tolerance, and not by collapsing: collapsed triangles are left out
// of the normal figures, so a mesh squeezed flat or to a point would pass
// (the paper's `current` variant does that to armadillo and bunny00).
bool converged(const Figures& figures, double tolerance_deg, Eigen::Index triangles);

struct Deformation {
  Deformation(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
              const IterationCallback& callback, Vertices near = Vertices());

  const PolygonMesh& mesh;  // in the unit box
  const std::vector<int>& given_labels;
  const DeformOptions& options;
  const IterationCallback& callback;
  Stopwatch total, phase;  // the whole run; the current entry of PhaseSeconds

  DeformResult result;                // labels: the given ones, unlabelled faces filled, then any repair
  std::vector<int> nearest;           // per polygon face: the axis nearest its normal
  std::vector<int> filled_labels;     // the given labels, unlabelled faces filled
  Triangulation triangulation;
  std::vector<int> triangle_labels;   // result.labels per triangle
  int n = 0;                          // vertices
  Laplacian laplacian;                // of `weights`, with `shift` on the diagonal once assembled
  SparseCholesky factorization;       // of the input's Laplacian (analysed here)
  // Without a start, the analysis of the Laplacian's pattern runs on a
  // thread of its own while the members below are built (B0: 5 ms each).
  std::future<void> analysis;
  Components parts;
  Eigen::MatrixX3d centroids;         // of the input's components
  QualityMeasure quality;
  Vertices x;                         // the current positions

  // The input's factorisation is not held (freed, or deferred by a run
  // starting near a polycube): restore_factorization() makes it.
  bool factorization_released = false;
  CotangentWeights weights;
  double shift = 0.0;

  // Never worse than the input (docs/design.md section 2.6): a robust run
  // whose last state folds more edges than the input, or flips more faces
  // than its labels did at the start, returns the latest state that does
  // neither; the input itself qualifies, so there is always one.
  bool keep_acceptable = false;
  int start_flipped = 0;
  Vertices acceptable_x;
  std::vector<int> acceptable_labels;
  int untangled_at = 0;  // the iteration whose positions were untangled
  // An exact polycube of labels that differ from these on a few faces, to
  // flatten from before fitting (flatten_near, flatten_stage.h); empty: none,
  // or read already (freed once the run's first iteration has tried it).
  Vertices near;
  NearStart near_start;
  // Stop at the first flattening attempt that the flat solve alone does not
  // make exact (DeformResult::handed_over): labels that do not flatten
  // without help, at a scale where the coarse route (coarse_to_fine.h)
  // costs a fraction of untangling them here.
  bool hand_over_unflat = false;

  // An iteration's time goes to its stage (StageSeconds), less its
  // measurement and the flattening and untangling it did, which are stages
  // of their own (`set_apart`: their seconds in this iteration).
  StageCost* stage = nullptr;
  Stopwatch iteration_clock;
  double set_apart = 0.0;

  const Triangles& triangles() const { return triangulation.triangles; }

  // Puts a solution back where the mesh stands: every component's centroid
  // where it was, isolated vertices where they were. Throws Error on a
  // non-finite solution.
  Vertices place(const Eigen::MatrixX3d& solution) const;
  // place() of a back-substitution with `cholesky` (counted in the result).
  Vertices solve(const SparseCholesky& cholesky, const Eigen::MatrixX3d& rhs);

  // The input's factorisation freed while other systems are factorised (the
  // flat charts'), so that the two are never in memory together, and
  // restored when it is needed again: the same matrix and ordering give the
  // same factor (a deferred one is analysed then).
  void release_factorization();
  void restore_factorization();
  // The analysis of the input Laplacian's pattern, for the variant.
  void analyze();

  // New labels per polygon face: result.labels, triangle_labels and the
  // measurement's labels.
  void set_labels(std::vector<int> face_labels);
  // result.labels spread to their triangles.
  std::vector<int> per_triangle(const std::vector<int>& face_labels) const;

  // The set-up's time (StageSeconds::set_up): called once, before the first
  // iteration.
  void begin_iterations();

  // Measures x (from `states` = face_states(x) when given), keeps it if
  // acceptable, charges the iteration's time to `stage` and reports to the
  // callback; false when the run must stop.
  bool finish_iteration(int iteration, const FaceStates* states = nullptr);

  // The result: the kept state, the relabelled, unconverged and flipped
  // faces, the final figures and, with DeformOptions::time_references, the
  // reference timings.
  DeformResult conclude();
};

}  // namespace polycube
