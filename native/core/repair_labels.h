// Local repair of a labeling that breaks the polycube conditions
// (validate_labels): small moves, each kept only if it lowers the number of
// violations, cheapest in label energy first.
#pragma once

#include <vector>

#include "core/alpha_expansion.h"
#include "core/mesh_adjacency.h"

namespace polycube {

std::vector<int> repair_labels(const MeshAdjacency& adjacency, const LabelEnergy& energy, std::vector<int> labels,
                               int rounds);

}  // namespace polycube
