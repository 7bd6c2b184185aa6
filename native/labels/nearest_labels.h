// Labels every polygon face by the axis nearest its (Newell) normal: the
// default for unlabelled faces, and `--labels nearest` on the command line.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

std::vector<int> nearest_labels(const PolygonMesh& mesh);

}  // namespace polycube
