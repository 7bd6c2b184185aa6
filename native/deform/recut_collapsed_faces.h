// Collapsed faces, with the ring of faces around them, labelled again by the
// labeller's energy, for a further run (docs/design.md section 2.6, stage 8).
//
// relabel_collapsed_faces.h moves a chart boundary past the faces a polycube
// collapsed: each takes a neighbouring chart's label. That cannot open a thin
// part the labeller gave one chart (the cow's tail, the bull's horns): most
// of its collapsed faces have no neighbour of another chart, and no
// neighbouring chart has the labels its sides need. Cutting the collapsed
// faces again with the labeller's energy (fidelity to the input's normals,
// compact boundaries, recut_region.h) gives them the charts their normals
// ask for; the ring around them lets the new boundaries settle off the
// collapsed strip. No label is barred: a face that collapsed only because
// its neighbours did can keep its own.
//
// Inputs:
//   neighbours  face_neighbours (mesh_adjacency.h)
//   energy      the labeller's (label_energy.h) for these faces
//   collapsed   per polygon face, 1 when collapsed
//   rings       rings of faces added around the collapsed ones
// In/out:
//   labels      per polygon face, 0..5
// Returns the faces relabelled, ascending.
#pragma once

#include <vector>

#include "labels/alpha_expansion.h"

namespace polycube {

std::vector<int> recut_collapsed_faces(const std::vector<std::vector<int>>& neighbours, const LabelEnergy& energy,
                                       const std::vector<char>& collapsed, std::vector<int>& labels, int rings = 1);

}  // namespace polycube
