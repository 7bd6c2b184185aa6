#include "core/repair_labels.h"

namespace polycube {

std::vector<int> repair_labels(const MeshAdjacency&, const LabelEnergy&, std::vector<int> labels, int) {
  return labels;
}

}  // namespace polycube
