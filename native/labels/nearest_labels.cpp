#include "labels/nearest_labels.h"

#include "labels/axis.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"

namespace polycube {

std::vector<int> nearest_labels(const PolygonMesh& input) {
  const UnitBoxMesh unit(input);  // scale independence (unit_box.h)
  const PolygonMesh& mesh = unit.mesh();
  std::vector<int> labels(mesh.faces.count());
  for (int f = 0; f < mesh.faces.count(); ++f) labels[f] = nearest_axis(newell_normal(mesh.vertices, mesh.faces, f));
  return labels;
}

}  // namespace polycube
