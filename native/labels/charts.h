// Charts (docs/design.md section 3): the connected sets of faces with one label,
// connected through shared edges (touching at a vertex only does not join
// two faces), and how charts meet: along boundaries and at corners.
#pragma once

#include <array>
#include <vector>

#include "mesh/mesh_adjacency.h"

namespace polycube {

struct Charts {
  std::vector<int> of_face;  // chart per face
  std::vector<int> label;    // per chart, 0..5
  std::vector<int> faces;    // face count per chart

  int count() const { return static_cast<int>(label.size()); }
};

// labels: one per face, 0..5 (no unlabelled faces: fill them first). Charts
// are numbered in the order of their lowest face, so the numbering is
// deterministic and stable under relabelling elsewhere.
Charts charts(const MeshAdjacency& adjacency, const std::vector<int>& labels);

// The faces of each chart, increasing.
std::vector<std::vector<int>> chart_faces(const Charts& charts);

// One pair of charts that share at least one edge: a chart boundary.
struct ChartBoundary {
  std::array<int, 2> charts;  // smaller first
  std::vector<int> edges;     // the shared edges, increasing
};

// Every chart boundary, ordered by chart pair.
std::vector<ChartBoundary> chart_boundaries(const MeshAdjacency& adjacency, const Charts& charts);

// Per chart, 1 when it reaches the mesh border (an edge with one face). Such
// a chart has an open side where its missing neighbours would be, so the
// four-neighbour rule does not apply to it (docs/design.md section 3.2): the
// rule is a condition on closed surfaces, and a flat sheet is a polycube of
// one chart.
std::vector<char> charts_with_open_side(const MeshAdjacency& adjacency, const Charts& charts);

// The faces of `chart` within `depth` edge-steps of the `seed` faces (seed
// faces of other charts are skipped), increasing: a band along a chart
// boundary, for the repairs to move. neighbours: face_neighbours.
std::vector<int> chart_band(const std::vector<std::vector<int>>& neighbours, const Charts& charts, int chart,
                            const std::vector<int>& seed, int depth);

// The distinct charts around vertex v, increasing.
std::vector<int> charts_at_vertex(const MeshAdjacency& adjacency, const Charts& charts, int v);

}  // namespace polycube
