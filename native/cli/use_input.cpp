#include "cli/use_input.h"

#include "io/labels_io.h"
#include "io/read_mesh.h"

namespace polycube {

UseInput read_use_input(const Arguments& arguments) {
  UseInput input;
  input.mesh = read_mesh(arguments.input(0));
  const PolygonMesh polycube = read_mesh(arguments.input(1));
  if (polycube.faces.indices != input.mesh.faces.indices || polycube.faces.offsets != input.mesh.faces.offsets)
    throw Error(arguments.input(1) + " does not have the faces of " + arguments.input(0) +
                ": give the polycube `polycube deform --output` wrote for this mesh");
  input.polycube = polycube.vertices;
  if (arguments.has("labels")) input.labels = read_labels(arguments.get("labels", ""), input.mesh.faces.count());
  return input;
}

}  // namespace polycube
