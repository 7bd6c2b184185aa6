// A mesh of a million triangles deformed through a coarse one (docs/design.md
// section 2.8): decimated with its charts kept (decimate_charts.h), the
// coarse mesh deformed by every stage of the robust variant (its further runs
// and last resort included), its polycube carried back to the fine vertices,
// and the fine mesh's own run started from there (flatten_near,
// flatten_stage.h), where it only flattens what the carrying left bent,
// relaxes and polishes. That run and stage 8's further runs after it start
// near a polycube or not at all (NearStart::or_nothing): from the input each
// would be the whole run the route saves.
//
// Why: at scale the robust variant's time goes to untangling the slivers its
// flat charts collapse and to stage 8's further runs, each a whole run
// (bunny00 refined 16 times, nearest labels: half an hour, 1.2 million
// triangles). On the coarse mesh these cost what they cost on the model
// itself, seconds, and the polycube they reach is the same wherever the fine
// mesh only adds vertices on the same surface.
//
// When: the robust variant, from kCoarseFromRatio times
// DeformOptions::coarse_triangles triangles on, once the mesh's own run has
// shown at its first flattening attempt that its labels do not flatten
// without help (Deformation::hand_over_unflat). Labels that do flatten (B0
// refined 64 times) are deformed as before, bit for bit: there the fine run
// costs about what the route would, and keeps its exact figures.
//
// Input: a mesh in the unit box, its labels per polygon face (-1..5), the
// run's options and callback (iterations of the coarse run are shown with
// their positions carried to the fine vertices), and the mesh's own run that
// handed over (its cost and iterations count in the result). Output: false
// when the decimation cannot get far enough, or the coarse or the fine run
// does not end exact; then `result` holds only what was spent, for the
// caller, who deforms the mesh itself. Else true, `result` the fine run's
// (its labels those it ran on, its relabelled faces those the coarse run
// relabelled too), and `finished` what its polish needs.
#pragma once

#include <memory>
#include <vector>

#include "deform/deform.h"

namespace polycube {

struct FinishedRun;

// The fine mesh must have at least this many times the coarse triangles: a
// run on a mesh a quarter the size saves less than the carrying costs in
// figures (what the fine run must still flatten and untangle).
constexpr double kCoarseFromRatio = 4.0;

// The coarse run's stage 5 untangles a result once more only above this
// share of its area collapsed (DeformOptions::untangle_again_above, 0.5%
// at the models' own size): its first run and last resort, which collapse
// several percent, still do; its further runs, which move the labels past
// what collapsed under 2%, leave the rest to the next run's relabelling,
// where the second pass was half of each run's time. Armadillo refined 16
// times, nearest labels: the coarse run 21.6 -> 18.2 s, 800 -> 772
// collapsed faces at the end (0.073% -> 0.072% of the area), edge and area
// error 0.264/0.399 -> 0.267/0.401; refined 4 times: 35 -> 27.5 s, 149 ->
// 132 faces (0.051% -> 0.048%), errors 0.261/0.393 -> 0.261/0.392. Bunny00
// and fandisk refined: bit for bit. At 1% the armadillo refined 16 times
// ended at 0.107%: which run's second pass is skipped moves the labels the
// further runs reach.
constexpr double kCoarseUntangleAgainAbove = 0.02;

// Whether the route applies to a mesh of this many triangles (above).
bool coarse_route_applies(const DeformOptions& options, Eigen::Index triangles);

bool coarse_to_fine(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                    const IterationCallback& callback, const DeformResult& handed_over, DeformResult& result,
                    std::unique_ptr<FinishedRun>& finished);

}  // namespace polycube
