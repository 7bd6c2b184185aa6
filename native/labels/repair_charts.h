// Local repair of a labeling that breaks the polycube conditions
// (validate_labels). Violations are taken smallest chart first; for the first
// one some candidate move improves, the move with the least energy added per
// unit of score removed is applied, and the labeling is validated again. A
// move costly enough to relabel a large chart (over 3% of the surface's
// energy per unit) waits while one of the next few violations has a cheaper
// fix: the cow's whole back once turned -X to fix a chart of 6 faces.
// Candidate moves:
// - a chart with too few neighbours: the whole chart, or it and one
//   neighbour, takes another label (merging into a neighbour, or becoming a
//   chart its neighbours can frame), or it and all its neighbours but the
//   largest join the largest (a feature too small for its own charts);
// - opposite charts side by side: the smaller chart takes an orthogonal label;
//   or a band of faces along their boundary (on either side) does, as one
//   label, each face's own best orthogonal label, or a graph cut among the
//   orthogonal labels, so a strip separates them; or the smaller chart and
//   its neighbours but the largest join the largest;
// - a corner of four or more charts: the faces of one chart around the
//   vertex take the label of another chart there.
// When no single move helps, the few least bad ones are each followed by a
// short greedy run, and the first that ends lower is kept (a strip along the
// rim of a thin ear leaves small charts that the next moves clean up).
// The score counts each missing neighbour, each opposite pair (twice) and each
// chart beyond three at a corner; only moves that lower it are kept, so the
// repair ends. Charts that reach the mesh border are not held to four
// neighbours (charts_with_open_side): on an open mesh that rule would merge
// whole sheets into one label. Deterministic.
#pragma once

#include <vector>

#include "labels/alpha_expansion.h"
#include "labels/face_geometry.h"
#include "labels/violation_score.h"
#include "mesh/mesh_adjacency.h"

namespace polycube {

// energy: the labeller's, to choose between moves that fix equally much.
// max_moves: at most this many moves. The candidates tried are also bounded
// (about 1e8 face visits in all), so a mesh full of violations no move can fix
// costs seconds, not hours; the bound is a count, so the result stays
// deterministic.
std::vector<int> repair_charts(const MeshAdjacency& adjacency, const LabelEnergy& energy, std::vector<int> labels,
                               int max_moves);

// Tiny charts (fewer than three faces, or under 0.1% of the area: noise, and
// more than the deformation can flatten) take the label of the neighbour that
// costs least energy, smallest first, where that does not raise the violation
// score. A chart whose faces all lie flat on its axis already is never tiny:
// it is a wall of a model built from boxes (two long triangles, or a narrow
// strip), and merged, the polycube would turn it through 90 degrees.
std::vector<int> merge_tiny_charts(const MeshAdjacency& adjacency, const LabelEnergy& energy,
                                   const FaceGeometry& geometry, std::vector<int> labels, int max_moves);

// Fewer charts where small ones only add detail: each chart under
// `max_share` of the area or of fewer than three faces (tiny, as above, but
// left by merge_tiny_charts because no neighbour's label alone keeps the
// polycube conditions), smallest first, takes a neighbour's label, and a
// short repair run follows when that broke the polycube conditions; the
// first such merge that ends with fewer charts and no higher violation score
// is kept, until none is.
std::vector<int> simplify_charts(const MeshAdjacency& adjacency, const LabelEnergy& energy,
                                 const FaceGeometry& geometry, std::vector<int> labels, double max_share,
                                 int max_moves);

}  // namespace polycube
