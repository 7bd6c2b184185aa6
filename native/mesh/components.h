// Connected components of the vertices through the triangles. The Laplacian
// lets each component float by a translation, so the solver fixes each one's
// centroid separately. Vertices in no triangle get component -1.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct Components {
  std::vector<int> of_vertex;  // component per vertex, -1 when isolated
  int count = 0;
};

Components components(int vertex_count, const Triangles& triangles);

}  // namespace polycube
