// Collapsed faces take a neighbouring chart's label, for a second run
// (docs/design.md section 2.6, stage 8).
//
// An exact polycube collapses a face where its chart has no room for it: a
// tooth of a chart boundary that doubles back, a strip one face wide, a
// vertex enclosed by one boundary line. Labels cannot tell these from the
// mesh alone (labels/realisability.h finds only some); the polycube shows
// them. Giving each collapsed face the label most of its uncollapsed
// neighbours of another chart have moves the boundary past it, and a second
// run from the input with those labels usually has room for it (knot2: 0.58%
// of the area collapsed, then 0.40%; eight 1.2%, then none).
//
// Inputs:
//   neighbours  face_neighbours (mesh_adjacency.h)
//   collapsed   per polygon face, 1 when collapsed
// In/out:
//   labels      per polygon face, 0..5; a collapsed face takes, of its
//               uncollapsed neighbours' labels other than its own and its
//               opposite and other than any neighbour's opposite, the most
//               frequent (ties: the lowest); faces with none such wait for a
//               neighbour relabelled in an earlier sweep (at most
//               max_sweeps), each sweep decided from the labels before it,
//               a face whose neighbour took the opposite label earlier in
//               the sweep waiting too. Opposite labels side by side lie back
//               to back in the polycube, their edge folded unless one of the
//               two stays collapsed, and a run folding more edges than its
//               input is refused (keep_opposites_apart.h).
// Returns the faces relabelled, ascending.
#pragma once

#include <vector>

namespace polycube {

std::vector<int> relabel_collapsed_faces(const std::vector<std::vector<int>>& neighbours,
                                         const std::vector<char>& collapsed, std::vector<int>& labels,
                                         int max_sweeps = 10);

}  // namespace polycube
