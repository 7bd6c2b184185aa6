// What the labeller's chart merges weigh each face by (docs/design.md
// section 3.3): its area, and the label its normal already lies on.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct FaceGeometry {
  std::vector<double> areas;
  // The label whose axis the face's normal lies within kOnAxisDegrees of, or
  // -1: such a face is flat on its axis before any deformation (the walls of
  // a model built from boxes).
  std::vector<int> on_axis;
};

constexpr double kOnAxisDegrees = 1.0;

FaceGeometry face_geometry(const Vertices& vertices, const PolygonFaces& faces);

}  // namespace polycube
