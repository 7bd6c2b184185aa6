// Uniform refinement with OpenSubdiv, so a coarse mesh (a 12-triangle box, a
// low-poly model) has the vertices it needs to bend into a polycube. Every
// child face inherits its parent's label.
//
// Schemes:
// - bilinear: positions interpolated linearly, so every new vertex lies on the
//   input surface; all-triangle meshes split 1 -> 4 triangles, others into quads.
// - loop: Loop subdivision (triangle meshes only), smooth.
// - catmark: Catmull-Clark, smooth, all quads after one level.
#pragma once

#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace polycube {

enum class RefineScheme { kBilinear, kLoop, kCatmark };

RefineScheme parse_refine_scheme(const std::string& name);  // bilinear | loop | catmark, else Error

struct Refined {
  PolygonMesh mesh;
  std::vector<int> labels;       // per child face; empty when no labels were given
  std::vector<int> parent_face;  // the input face each child face comes from
};

constexpr int kMaxRefineLevels = 8;

// labels: per input face (-1..5) or empty. Throws Error on levels outside
// 1..kMaxRefineLevels, a result over 20 million faces, Loop on a mesh with
// non-triangles, input check_input rejects, or topology OpenSubdiv refuses.
Refined refine(const PolygonMesh& mesh, const std::vector<int>& labels, int levels, RefineScheme scheme);

}  // namespace polycube
