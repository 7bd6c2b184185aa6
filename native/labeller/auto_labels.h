// Automatic labeling (docs/design.md section 3.3): labels that make a clean
// polycube wherever the shape allows.
//
// 0. Straighten the shape (straighten.h) so its normals gather on the axes;
//    the steps below read the straightened normals, not the input's.
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
// 4. Relabel the triangles that flat charts would squeeze onto a line
//    (labels/squeezed_triangles.h), and repair again, a few rounds.
// 5. Open components that mostly look one way (an eyeball, a leaf) take
//    one label: one flat chart each (labels/open_caps.h).
// 6. Merge away charts of one or two faces the repair could not, and at low
//    detail small charts (simplify_below), each with a short repair.
// 7. A chart whose faces, together, face away from its axis (a reversed
//    chart, labels/realisability.h) gives them their own nearest axes, and
//    a repair follows; kept when the labeling is then less invalid.
// Deterministic: the same mesh and options give the same labels.
#pragma once

#include <vector>

#include "labels/label_energy.h"
#include "mesh/mesh.h"

namespace polycube {

struct AutoLabelOptions {
  // The options for one knob a user understands, `detail` in 0..1: 0 gives a
  // few large charts (a polycube a modeller would sketch), 1 many small ones
  // that follow every feature; 0.5 is the default below. It sets the
  // compactness (3 at 0, 0.3 at 0.5, 0.03 at 1), the straightening's
  // smoothing rings and reach (x4, x1, x1/4) and, below 0.5, the share of the area under
  // which charts are merged away (1% at 0, 0.5% at 0.25, none from 0.5).
  // Throws Error outside 0..1.
  static AutoLabelOptions with_detail(double detail);

  // Weight of chart boundary length against fidelity to the normals: larger
  // gives fewer, rounder charts and ignores smaller features.
  double compactness = kDefaultCompactness;
  bool repair = true;              // steps 3 and 4
  int repair_moves = 200;          // at most this many repair moves (each fixes at least one violation)
  int straighten_iterations = 20;  // step 0; 0 reads the input's normals
  // Step 0's smoothing (straighten.h) reaches this share of the square root
  // of the surface area, in rings of faces of the mesh's mean edge length,
  // and never fewer than `straighten_rings` rings: the same shape, finer
  // meshed, is smoothed over the same surface and gets the same charts
  // (Suzanne with two levels of subdivision: 36 charts at 3 rings, 18 at 8,
  // as Suzanne's 12 at 3). Meshes coarser than 3 rings per reach keep 3.
  int straighten_rings = 3;
  double straighten_reach = 0.082;
  // Step 6: charts under this share of the area (and charts of fewer than
  // three faces) merge into a neighbour where a short repair keeps the
  // polycube conditions (repair_charts.h, simplify_charts); 0: only those
  // of fewer than three faces. Needs `repair`.
  double simplify_below = 0.0;
};

// One label 0..5 per face. Throws Error on input check_input rejects.
// `straightened`, when given, receives the straightened positions of step 0:
// a shape close to the polycube of these labels, from which the deformation
// can start (DeformOptions::start).
std::vector<int> auto_labels(const PolygonMesh& mesh, const AutoLabelOptions& options = {},
                             Vertices* straightened = nullptr);

}  // namespace polycube
