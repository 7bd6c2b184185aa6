// A shape whose normals gather on the axes, for the labeller to read its
// labels from (docs/design.md section 3.4).
//
// Labels read off the input's normals are a mosaic on organic shapes: a limb
// seen at 45 degrees flips between two axes face by face, and no polycube
// realises that without collapsing much of it. Labels read off a shape that
// is already nearly a polycube follow its flat sides and sharp edges
// instead. This is the rotation-driven pre-deformation of Gregson, Sheffer
// and Zhang (2011) in the surface form of our solver: every iteration each
// triangle takes, as its target, the axis nearest its normal smoothed over
// its neighbourhood, and the shape is re-solved as rigidly as possible
// (fitted_rotations, input Laplacian factorised once). The smoothing is
// bilateral: neighbours count by area and by how much their normals agree,
// so the two sides of a thin part (an ear, a blade) never average out, which
// plain averaging does and which flattens thin parts to nothing.
//
// Inputs:
//   input      #V by 3 positions
//   triangles  #T by 3 corner indices
//   options    iterations, smoothing rings
// Output: #V by 3 straightened positions (each component's centroid kept).
#pragma once

#include "mesh/mesh.h"

namespace polycube {

struct StraightenOptions {
  int iterations = 20;
  // Rounds of bilateral smoothing of the normals per iteration: larger makes
  // bigger flat sides and ignores smaller features.
  int rings = 3;
};

Vertices straighten(const Vertices& input, const Triangles& triangles, const StraightenOptions& options = {});

}  // namespace polycube
