// A UV map from the polycube (the use of a polycube for texturing): every
// chart of the polycube is one island, its UVs the polycube's positions in
// the chart's plane, so the distortion inside an island is exactly that of
// the map from the mesh onto its polycube, and every island has the same
// texel density (the polycube's own scale). Islands are packed without
// overlap into the unit square.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct PolycubeUvOptions {
  bool pack = true;        // false: islands stay where the projection put them (overlapping)
  // Re-solve each island's inside to keep the input's angles (relax_islands.h): the
  // polycube then only decides islands and seams. Off: UVs are the polycube's positions.
  bool relax = false;
  // With relax: merge neighbouring islands whose union unfolds as well (merge_islands.h),
  // a merge costing at most this much angle distortion; negative: no merging.
  double merge_slack = -1.0;
  double padding = 0.01;   // gap between packed islands, relative to the square root of their area
};

struct PolycubeUv {
  CornerUvs uvs;  // per corner (faces.indices order)
  std::vector<int> island_of_face;
  std::vector<int> label_of_face;  // the label each face was projected by (the solver's final one)
  int islands = 0;                 // = charts that carry area (fewer after merging)
};

// Inputs:
//   input     the mesh
//   polycube  #V by 3 positions on its polycube (same vertices, same faces)
//   labels    per face 0..5 or -1, or empty (see polycube_surface)
// A chart all of whose faces were collapsed has no area of its own: its faces
// join a neighbouring island (their UVs are then a segment or a point there).
// Throws Error on a polycube that does not fit the mesh or is folded.
PolycubeUv polycube_uv(const PolygonMesh& input, const Vertices& polycube, const std::vector<int>& labels,
                       const PolycubeUvOptions& options = {});

}  // namespace polycube
