// Some faces cut again by alpha-expansion (alpha_expansion.h), everything
// else held: the cut runs on the region alone, and each pair with a held face
// becomes a data cost of the face inside, so the region's new charts meet the
// charts around it as the labeller's energy wants.
//
// Why: two repairs relabel a patch as a whole rather than face by face. The
// labeller's repair (repair_charts.h) gives a strip between two opposite
// charts smooth boundaries of its own, among the labels off their axis; stage
// 8 (docs/design.md section 2.6) gives a cluster of collapsed faces (a thin
// part labelled with one chart, flattened to a line) the charts its normals
// ask for (recut_collapsed_faces.h).
//
// Inputs:
//   energy  the labeller's (label_energy.h), one site per face
//   labels  per face, 0..5
//   region  the faces to cut again
//   axis    0..2: labels on this axis are barred from the region; -1: none
// Returns `labels` with the region's faces cut again.
#pragma once

#include <vector>

#include "labels/alpha_expansion.h"

namespace polycube {

std::vector<int> recut_region(const LabelEnergy& energy, const std::vector<int>& labels, const std::vector<int>& region,
                              int axis = -1);

}  // namespace polycube
