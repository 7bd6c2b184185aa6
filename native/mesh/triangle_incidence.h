// The triangles around each vertex, as offsets into one flat list: what a
// local re-measurement (fold_free_step) or a growing region (flatten_charts)
// walks from a vertex.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct TriangleIncidence {
  std::vector<int> offsets, triangles;  // triangles[offsets[v] .. offsets[v + 1]) touch vertex v

  TriangleIncidence(Eigen::Index vertex_count, const Triangles& t) : offsets(vertex_count + 1, 0) {
    for (Eigen::Index f = 0; f < t.rows(); ++f)
      for (int k = 0; k < 3; ++k) ++offsets[t(f, k) + 1];
    for (Eigen::Index v = 0; v < vertex_count; ++v) offsets[v + 1] += offsets[v];
    triangles.resize(offsets.back());
    std::vector<int> next(offsets.begin(), offsets.end() - 1);
    for (Eigen::Index f = 0; f < t.rows(); ++f)
      for (int k = 0; k < 3; ++k) triangles[next[t(f, k)]++] = static_cast<int>(f);
  }
};

}  // namespace polycube
