#include "labels/nearest_labels.h"

#include "labels/axis.h"
#include "mesh/triangulate.h"

namespace polycube {

std::vector<int> nearest_labels(const PolygonMesh& mesh) {
  std::vector<int> labels(mesh.faces.count());
  for (int f = 0; f < mesh.faces.count(); ++f) labels[f] = nearest_axis(newell_normal(mesh.vertices, mesh.faces, f));
  return labels;
}

}  // namespace polycube
