// The polycube deformation of DESIGN.md section 2: iterate "rotate every
// triangle's normal onto its label axis, then solve L x = b" until the largest
// normal deviation is below the tolerance or the iteration limit is reached.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/mesh.h"
#include "core/quality.h"

namespace polycube {

// Which Laplacian the Poisson solve uses. Every fixed point is an exact polycube
// whatever the weights, so both reach the same shapes; they differ in cost and
// robustness.
//
// `robust` (the default) is ours, not the paper's; see robust_step.h for why
// and what it does. `fixed` and `current` are the plain method, kept for
// comparison: their fixed points are exactly the polycubes of the labels.
enum class Variant {
  kFixed,    // built from the input once, factorised once: one back-substitution per iteration
  kCurrent,  // rebuilt from the current mesh every iteration, as in the paper
  kRobust,   // fold-free: input-shape fitting, then the paper's step under a step control
};

Variant parse_variant(const std::string& name);  // "robust" | "fixed" | "current", else Error
const char* variant_name(Variant variant);

struct DeformOptions {
  int iterations = 100;
  double tolerance_deg = 0.5;  // 0 runs every iteration: nothing is below it
  Variant variant = Variant::kRobust;
};

struct PhaseSeconds {
  double total = 0, assemble = 0, factorize = 0, rotations = 0, solve = 0, measure = 0;
};

struct DeformResult {
  Vertices positions;
  std::vector<int> labels;  // per polygon face, unlabelled ones replaced by their nearest axis
  Figures figures;          // of `positions`
  int iterations = 0;
  bool converged = false;   // largest normal deviation below the tolerance
  bool stopped = false;     // the callback asked to stop
  int unlabelled_faces = 0;
  int triangles = 0;
  // Polygon faces (ids into the input's faces, ascending) that end above the
  // tolerance, and those of them that are flipped (a visible fold). A polygon
  // is listed when any of its triangles is; collapsed triangles are not.
  std::vector<int> unconverged_faces;
  std::vector<int> flipped_faces;
  PhaseSeconds seconds;
};

// Called after each iteration with its number (from 1), the positions and their
// figures; returning false stops the run, keeping what is done.
using IterationCallback = std::function<bool(int iteration, const Vertices& positions, const Figures& figures)>;

// Labels are per polygon face, -1..5. Throws Error on input check_input rejects
// and when a linear solve fails.
DeformResult deform(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options = {},
                    const IterationCallback& callback = {});

}  // namespace polycube
