// Labels only mean something against outward normals: +X on a face whose
// winding points inward asks the solver to turn the surface inside out. This
// check says whether the winding is consistent, whether it can be made so
// (non-orientable meshes such as a Moebius strip cannot, and are reported,
// not "fixed"), whether closed parts are wound inward, and whether given
// labels mostly oppose the face normals (labels made for the other winding).
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct Orientation {
  bool orientable = true;       // some winding makes every two faces on an edge run it opposite ways
  bool consistent = true;       // the given winding already does
  int inconsistent_edges = 0;   // two-face edges both faces walk the same way
  int components = 0;           // connected through two-face edges
  int closed_components = 0;    // without boundary or non-manifold edges
  int inward_components = 0;    // closed, consistent, and enclosing negative volume
  // With labels: the share of the area whose normal points away from its
  // label's axis (dot < 0), and whether that is most of it.
  double area_against_labels = 0.0;
  bool labels_opposite = false;

  bool inward() const { return inward_components > 0; }
};

// labels: optional, one per face, -1..5 (-1 faces are left out of the share).
// Throws Error on input check_input rejects.
Orientation orientation(const PolygonMesh& mesh, const std::vector<int>* labels = nullptr);

// Each label turned to its opposite axis (+X <-> -X, ...), -1 kept: the
// labels for the other winding of the same surface.
// Throws Error on a label outside -1..5.
std::vector<int> flip_labels(const std::vector<int>& labels);

}  // namespace polycube
