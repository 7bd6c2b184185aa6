// Local repair of a labeling that breaks the polycube conditions
// (validate_labels). For the first violation that some small move improves,
// the move that lowers the violation score most (then the label energy) is
// applied, and the labeling is validated again:
// - a chart with too few neighbours: the whole chart takes another label
//   (merging into a neighbour, or becoming a chart its neighbours can frame);
// - opposite charts side by side: the smaller chart takes an orthogonal label,
//   or a band of faces along their boundary (one or two faces deep, on either
//   side) does, so a third chart separates them;
// - a corner of four or more charts: the faces of one chart around the
//   vertex take the label of another chart there.
// The score counts each missing neighbour, each opposite pair (twice) and each
// chart beyond three at a corner; a move is kept only if it lowers it, so the
// repair ends. Deterministic.
#pragma once

#include <vector>

#include "core/alpha_expansion.h"
#include "core/mesh_adjacency.h"

namespace polycube {

// energy: the labeller's, to choose between moves that fix equally much.
// rounds: at most this many moves.
std::vector<int> repair_labels(const MeshAdjacency& adjacency, const LabelEnergy& energy, std::vector<int> labels,
                               int rounds);

// The score above (0 for a valid labeling); labels 0..5, one per face.
int violation_score(const MeshAdjacency& adjacency, const std::vector<int>& labels);

}  // namespace polycube
