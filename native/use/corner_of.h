// The polygon corner (index into PolygonFaces::indices) of face f at vertex v:
// where per-corner data (UVs) of a triangle of the split is found.
#pragma once

#include "mesh/mesh.h"

namespace polycube {

// The first such corner if the face repeats v; the face's first corner if it has none.
inline int corner_of(const PolygonFaces& faces, int f, int v) {
  for (int k = faces.offsets[f]; k < faces.offsets[f + 1]; ++k)
    if (faces.indices[k] == v) return k;
  return faces.offsets[f];
}

}  // namespace polycube
