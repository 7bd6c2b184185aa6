// Rejects input the solver cannot take, with one sentence that says what is
// wrong and where, before anything is allocated from it.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

// Throws Error for: no vertices or no faces, a face with fewer than 3 corners,
// an index out of range, a non-finite coordinate, offsets that do not describe
// the indices, and (when labels is not null) a label count different from the
// face count or a label outside -1..5.
void check_input(const PolygonMesh& mesh, const std::vector<int>* labels = nullptr);

}  // namespace polycube
