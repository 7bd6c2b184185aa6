// Connected components of the vertices through the triangles. The Laplacian
// lets each component float by a translation, so the solver fixes each one's
// centroid separately. Vertices in no triangle get component -1.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct Components {
  std::vector<int> of_vertex;  // component per vertex, -1 when isolated
  int count = 0;
};

Components components(int vertex_count, const Triangles& triangles);

// The centroid of each component's vertices (#components by 3).
Eigen::MatrixX3d component_centroids(const Vertices& x, const Components& components);

// `solution` moved so that every component's centroid is at `centroids`;
// isolated vertices take their positions from `rest`. What every solve of a
// singular Laplacian needs to be put back in place.
Vertices place_components(const Eigen::MatrixX3d& solution, const Vertices& rest, const Components& components,
                          const Eigen::MatrixX3d& centroids);

}  // namespace polycube
