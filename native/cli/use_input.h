// What `polycube uv` and `polycube remesh` read: the mesh, its polycube (same
// vertices and faces, as `polycube deform --output` writes it) and, optionally,
// the labels the solver ended with.
#pragma once

#include <string>
#include <vector>

#include "cli/arguments.h"
#include "mesh/mesh.h"

namespace polycube {

struct UseInput {
  PolygonMesh mesh;
  Vertices polycube;
  std::vector<int> labels;  // empty: read from the polycube's normals
};

struct UseInputPaths {
  std::string mesh, polycube, labels;  // labels empty: none given
};

// Declares the inputs IN POLYCUBE and --labels FILE.
void add_use_inputs(CLI::App& app, UseInputPaths& paths);

// Throws Error when the polycube's faces are not the mesh's.
UseInput read_use_input(const UseInputPaths& paths);

}  // namespace polycube
