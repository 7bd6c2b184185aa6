// What `polycube uv` and `polycube remesh` read: the mesh, its polycube (same
// vertices and faces, as `polycube deform --output` writes it) and, optionally,
// the labels the solver ended with.
#pragma once

#include <vector>

#include "cli/arguments.h"
#include "mesh/mesh.h"

namespace polycube {

struct UseInput {
  PolygonMesh mesh;
  Vertices polycube;
  std::vector<int> labels;  // empty: read from the polycube's normals
};

// Inputs IN POLYCUBE and option --labels FILE. Throws Error when the polycube's
// faces are not the mesh's.
UseInput read_use_input(const Arguments& arguments);

}  // namespace polycube
