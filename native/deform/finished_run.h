// What a robust run leaves for the polish of its result (polish_stage.h,
// docs/design.md section 2.6, item 10): its set-up (the triangulation, the
// measurement on the labels it ended with, the Laplacian assembled) and the
// flat charts it ended with, factorised. Built again from the same mesh,
// labels and positions, the polish's set-up and its three factorisations
// of the chart systems, with their orderings, took a fifth of B0's
// process; the run has them all already.
//
// The Deformation refers to the options, labels and callback held here
// (those of a further run, deform_any_scale.cpp, are gone once it
// returns); the callback is emptied when the run ends, so nothing calls
// back from a finished run.
#pragma once

#include <memory>
#include <vector>

#include "deform/chart_planes.h"
#include "deform/deform.h"
#include "deform/deformation.h"

namespace polycube {

struct FinishedRun {
  DeformOptions options;
  std::vector<int> labels;
  IterationCallback callback;
  // Concluded: its positions and result are the DeformResult returned
  // (moved out), its labels and measurement those of that result.
  std::unique_ptr<Deformation> deformation;
  // The robust run's last flat charts, factorised; null when it had none.
  std::unique_ptr<ChartPlanes> planes;
};

// deform_in_unit_box() (deform.h), keeping what the run leaves in `finished`;
// `near`, when not empty: Deformation::near, started from as `near_start`
// says; `hand_over_unflat`: Deformation's.
DeformResult deform_in_unit_box(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                                const IterationCallback& callback, std::unique_ptr<FinishedRun>& finished,
                                const Vertices& near = Vertices(),
                                NearStart near_start = NearStart(),
                                bool hand_over_unflat = false);

}  // namespace polycube
