// Automatic labeling (DESIGN.md section 3, issue 4): labels that make a clean
// polycube wherever the shape allows.
//
// 1. Start from the nearest axis of every face normal.
// 2. Minimise E = sum over faces of area * fidelity(normal, label axis)
//              + compactness * sum over edges between charts of length * h * V(a, b)
//    with alpha-expansion (graph cuts, Boykov-Veksler-Zabih): V is 1 between
//    orthogonal labels and larger between opposite ones, so opposite charts
//    rarely touch; edges across sharp creases cost less, so chart boundaries
//    follow the model's features; h is a length proportional to the model's
//    size, so the result does not depend on the mesh resolution.
// 3. Merge tiny charts into a neighbour (repair_charts.h), then repair what
//    still breaks the polycube conditions (validate_labels) with local moves:
//    relabel an ill-connected chart, a band of faces along an opposite
//    boundary, or the faces around a corner of four or more charts; a move is
//    kept only if it lowers the number of violations. Tiny charts the repair
//    left are merged last.
// Deterministic: the same mesh and options give the same labels.
#pragma once

#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct AutoLabelOptions {
  // Weight of chart boundary length against fidelity to the normals: larger
  // gives fewer, rounder charts and ignores smaller features.
  double compactness = 0.3;
  bool repair = true;        // step 3
  int repair_moves = 200;    // at most this many repair moves (each fixes at least one violation)
};

// One label 0..5 per face. Throws Error on input check_input rejects.
std::vector<int> auto_labels(const PolygonMesh& mesh, const AutoLabelOptions& options = {});

}  // namespace polycube
