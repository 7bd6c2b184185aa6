#include "cli/use_input.h"

#include "io/labels_io.h"
#include "io/read_mesh.h"

namespace polycube {

void add_use_inputs(CLI::App& app, UseInputPaths& paths) {
  app.add_option("IN", paths.mesh, "the mesh (.off, .obj, .ply)")->required()->type_name("");
  app.add_option("POLYCUBE", paths.polycube, "the mesh's polycube as `polycube deform --output` writes it")
      ->required()
      ->type_name("");
  app.add_option("--labels", paths.labels, "the labels the solver ended with (default: read from the\n"
                                           "polycube's normals)")
      ->type_name("FILE");
}

UseInput read_use_input(const UseInputPaths& paths) {
  UseInput input;
  input.mesh = read_mesh(paths.mesh);
  const PolygonMesh polycube = read_mesh(paths.polycube);
  if (polycube.faces.indices != input.mesh.faces.indices || polycube.faces.offsets != input.mesh.faces.offsets)
    throw Error(paths.polycube + " does not have the faces of " + paths.mesh +
                ": give the polycube `polycube deform --output` wrote for this mesh");
  input.polycube = polycube.vertices;
  if (!paths.labels.empty()) input.labels = read_labels(paths.labels, input.mesh.faces.count());
  return input;
}

}  // namespace polycube
