// The step control of the `robust` variant: a step that never turns a
// triangle over.
//
// The plain method jumps to the solution of each Poisson solve. On real
// models that jump folds triangles: `fixed` folds 43 faces of fandisk on the
// way (9 stay folded), 428 of the elephant, and even 4 of B0, which it then
// collapses; `current` diverges on the sphere from iteration 40. A line search
// on the whole step fails too: one face that wants to fold stops the whole
// mesh (B0 stalls at 89 degrees). So the step is shortened per vertex: every
// vertex moves the whole way unless that turns over a triangle that was not
// turned over, then only that triangle's corners get half the step, again
// and again, and after `max_halvings` they stand still. A triangle is turned
// over by the definition of the figures (quality.h): not collapsed, and its
// normal points away from its label's axis.
#pragma once

#include <optional>
#include <vector>

#include "deform/quality.h"
#include "mesh/triangle_incidence.h"

namespace polycube {

struct FoldFreeStep {
  Vertices positions;
  FaceStates states;       // of `positions`
  int limited = 0;         // vertices that did not go the whole way
  std::vector<char> held;  // triangles that would have turned over
};

// From `from` (whose states are `from_states`) towards `to`. Triangles turned
// over in `from` may stay so (they are not new folds). `incidence`, when
// given, keeps the triangles around each vertex (of `triangles`) between
// steps: built by the first step that folds, used by the later ones.
FoldFreeStep fold_free_step(const Vertices& from, const FaceStates& from_states, const Vertices& to,
                            const Triangles& triangles, const QualityMeasure& measure, int max_halvings = 6,
                            std::optional<TriangleIncidence>* incidence = nullptr);

}  // namespace polycube
