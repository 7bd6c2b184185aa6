#include "labels/face_geometry.h"

#include <cmath>

#include "labels/axis.h"
#include "mesh/triangulate.h"

namespace polycube {

FaceGeometry face_geometry(const Vertices& vertices, const PolygonFaces& faces) {
  const double on_axis_cos = std::cos(kOnAxisDegrees * M_PI / 180.0);
  FaceGeometry geometry;
  geometry.areas.resize(faces.count());
  geometry.on_axis.assign(faces.count(), -1);
  for (int f = 0; f < faces.count(); ++f) {
    const Eigen::Vector3d n = newell_normal(vertices, faces, f);
    const double norm = n.norm();
    geometry.areas[f] = 0.5 * norm;
    if (!(norm > 0.0)) continue;
    const int label = nearest_axis(n);
    if (n.dot(label_axis(label)) >= on_axis_cos * norm) geometry.on_axis[f] = label;
  }
  return geometry;
}

}  // namespace polycube
