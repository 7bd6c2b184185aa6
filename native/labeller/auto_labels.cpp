#include "labeller/auto_labels.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "labeller/straighten.h"
#include "labels/alpha_expansion.h"
#include "labels/axis.h"
#include "labels/faces_facing_away.h"
#include "labels/label_energy.h"
#include "labels/open_caps.h"
#include "labels/repair_charts.h"
#include "labels/squeezed_triangles.h"
#include "labels/validate_labels.h"
#include "mesh/check_input.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"

namespace polycube {
namespace {

// Rings of faces that reach `reach` times the square root of the surface
// area, at the mean length of the polygons' edges; at least `rings`, at most
// kMostRings (a ring costs one pass over the faces' neighbours, and 1M
// triangles would ask for 55 of them per iteration).
constexpr double kMostRings = 48;
int smoothing_rings(const PolygonMesh& mesh, const std::vector<double>& areas, double reach, int rings) {
  double area = 0.0, length = 0.0;
  for (double a : areas) area += a;
  const PolygonFaces& faces = mesh.faces;
  for (int f = 0; f < faces.count(); ++f)
    for (int k = 0, size = faces.size(f), first = faces.offsets[f]; k < size; ++k)
      length += (mesh.vertices.row(faces.indices[first + k]) - mesh.vertices.row(faces.indices[first + (k + 1) % size]))
                    .norm();
  length /= static_cast<double>(faces.indices.size());
  if (!(length > 0.0) || !(area > 0.0)) return rings;
  return std::max(rings, static_cast<int>(std::lround(std::min(reach * std::sqrt(area) / length, kMostRings))));
}

// The violations that make a labeling invalid (validate_labels.h: the
// polycube conditions and reversed charts).
int invalid_violations(const LabelValidation& validation) {
  return static_cast<int>(std::count_if(validation.violations.begin(), validation.violations.end(),
                                        [](const LabelViolation& v) { return makes_invalid(v.kind); }));
}

// Step 7: the faces of a reversed chart take the nearest axis of their own
// normals, and a repair follows; kept when fewer violations make the
// labeling invalid. The steps before judge faces one by one (step 3's
// faces facing away), and their merges can still leave a chart whose
// faces, taken together, face away from its axis (the dino: one +Y chart
// of 17 faces among 40 charts).
std::vector<int> unreverse_charts(const PolygonMesh& mesh, const MeshAdjacency& adjacency, const LabelEnergy& energy,
                                  const FaceGeometry& geometry, std::vector<int> labels, int moves) {
  const LabelValidation validation = validate_labels(mesh, labels);
  std::vector<int> moved = labels;
  bool reversed = false;
  for (const LabelViolation& v : validation.violations) {
    if (v.kind != ViolationKind::kReversedChart) continue;
    reversed = true;
    for (int f : v.faces) moved[f] = nearest_axis(newell_normal(mesh.vertices, mesh.faces, f));
  }
  if (!reversed) return labels;
  moved = repair_charts(adjacency, energy, std::move(moved), moves);
  moved = merge_tiny_charts(adjacency, energy, geometry, std::move(moved), moves);
  return invalid_violations(validate_labels(mesh, moved)) < invalid_violations(validation) ? moved : labels;
}

// Steps 3 to 7 of the labeller (docs/design.md section 3.3) on the graph
// cut's labels.
std::vector<int> repaired_labels(const PolygonMesh& mesh, const MeshAdjacency& adjacency,
                                 const Triangulation& triangulation, const LabelEnergy& energy,
                                 const FaceGeometry& geometry, std::vector<int> labels,
                                 const AutoLabelOptions& options) {
  const int vertex_count = static_cast<int>(mesh.vertices.rows());
  if (options.repair) {
    labels = merge_tiny_charts(adjacency, energy, geometry, std::move(labels), options.repair_moves);
    labels = repair_charts(adjacency, energy, std::move(labels), options.repair_moves);
    labels = merge_tiny_charts(adjacency, energy, geometry, std::move(labels), options.repair_moves);
    // Faces facing away from their labels, then what relabelling them broke.
    if (relabel_faces_facing_away(mesh, face_neighbours(adjacency, mesh.faces.count()), labels) > 0) {
      labels = repair_charts(adjacency, energy, std::move(labels), options.repair_moves);
      labels = merge_tiny_charts(adjacency, energy, geometry, std::move(labels), options.repair_moves);
    }
    // Squeezed triangles, then what relabelling them broke; a few rounds,
    // as each repair can leave new teeth. Kept only when the polycube
    // conditions hold as well as before. Only on labels that meet them: on
    // others the repairs would go on where the first ones stopped, merging
    // whole charts.
    const int violations = violation_score(adjacency, labels);
    std::vector<int> unsqueezed = labels;
    for (int round = 0; round < 3 && violations == 0; ++round) {
      if (unsqueeze_labels(vertex_count, triangulation.triangles, triangulation.face_of_triangle, unsqueezed) == 0)
        break;
      unsqueezed = repair_charts(adjacency, energy, std::move(unsqueezed), options.repair_moves);
      unsqueezed = merge_tiny_charts(adjacency, energy, geometry, std::move(unsqueezed), options.repair_moves);
    }
    if (violation_score(adjacency, unsqueezed) <= violations) labels = std::move(unsqueezed);
  }
  label_open_caps(mesh, adjacency, labels);
  if (options.repair)
    labels =
        simplify_charts(adjacency, energy, geometry, std::move(labels), options.simplify_below, options.repair_moves);
  if (options.repair)
    labels = unreverse_charts(mesh, adjacency, energy, geometry, std::move(labels), options.repair_moves);
  return labels;
}

}  // namespace

AutoLabelOptions AutoLabelOptions::with_detail(double detail) {
  if (!(detail >= 0.0 && detail <= 1.0)) throw Error("detail must be a number from 0 to 1");
  AutoLabelOptions options;
  options.compactness = 0.3 * std::pow(10.0, 1.0 - 2.0 * detail);
  const double smoothing = std::pow(4.0, 1.0 - 2.0 * detail);
  options.straighten_rings = std::max(1, static_cast<int>(std::lround(3.0 * smoothing)));
  options.straighten_reach *= smoothing;
  // Merging away small charts makes the coarse end of the knob what a user
  // asks for there (Suzanne at 0: 12 charts, a head and its muzzle), but it
  // loses limbs on organic models (the elephant's legs) and collapses more
  // there. Even charts under 0.1% of the area, merged at the default, left
  // armadillo and diplodocus with labels whose flat solve collapses more than
  // stage 3 accepts (docs/design.md section 2.6), so the default keeps every
  // chart the cut and the repair found but those of one or two faces (a
  // chart that small has no room to flatten: Suzanne's 28 charts, eight of
  // them of one or two faces, become 12).
  options.simplify_below = std::max(0.0, 0.01 * (1.0 - 2.0 * detail));
  return options;
}

std::vector<int> auto_labels(const PolygonMesh& input, const AutoLabelOptions& options, Vertices* straightened) {
  const UnitBoxMesh unit(input);  // scale independence (unit_box.h); `straightened` goes back below
  const PolygonMesh& mesh = unit.mesh();
  check_input(mesh);
  if (!(options.compactness >= 0.0) || !std::isfinite(options.compactness))
    throw Error("compactness must be a finite number of at least 0");
  const MeshAdjacency adjacency = mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows()));
  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  const FaceGeometry geometry = face_geometry(mesh.vertices, mesh.faces);
  const StraightenOptions so{options.straighten_iterations,
                             smoothing_rings(mesh, geometry.areas, options.straighten_reach, options.straighten_rings)};
  PolygonMesh straight{straighten(mesh.vertices, triangulation.triangles, so), mesh.faces};
  const LabelEnergy energy = label_energy(straight, mesh.vertices, adjacency, options.compactness);
  std::vector<int> labels(mesh.faces.count());
  for (int f = 0; f < mesh.faces.count(); ++f) {
    int best = 0;
    for (int l = 1; l < 6; ++l)
      if (energy.data(f, l) < energy.data(f, best)) best = l;
    labels[f] = best;  // the nearest axis (lowest label on ties)
  }
  labels = alpha_expansion(energy, std::move(labels));
  std::vector<int> repaired = repaired_labels(mesh, adjacency, triangulation, energy, geometry, labels, options);
  // Charts flat on their axes are kept however small (face_geometry.h);
  // where that leaves labels the polycube conditions reject, merging them
  // as any small chart is tried too, and the labels with fewer violations
  // kept (mpi, 52 faces: one chart otherwise).
  const bool on_axis = std::any_of(geometry.on_axis.begin(), geometry.on_axis.end(), [](int l) { return l >= 0; });
  int violations = options.repair ? invalid_violations(validate_labels(mesh, repaired)) : 0;
  if (on_axis && violations > 0) {
    FaceGeometry merged_geometry = geometry;
    merged_geometry.on_axis.assign(merged_geometry.on_axis.size(), -1);
    std::vector<int> merged = repaired_labels(mesh, adjacency, triangulation, energy, merged_geometry, labels, options);
    const int merged_violations = invalid_violations(validate_labels(mesh, merged));
    if (merged_violations < violations) {
      repaired = std::move(merged);
      violations = merged_violations;
    }
  }
  // The repairs trade fidelity to the normals for the polycube conditions:
  // where they end short of them, the trade bought nothing and the cut's own
  // labels flatten better (the cheese: exact, where the repaired labels'
  // run ends at 159 degrees; docs/design.md section 3.3).
  if (violations > 0) {
    AutoLabelOptions cut_only = options;
    cut_only.repair = false;
    repaired = repaired_labels(mesh, adjacency, triangulation, energy, geometry, std::move(labels), cut_only);
  }
  labels = std::move(repaired);
  if (straightened) *straightened = unit.box().from_unit(straight.vertices, mesh.vertices, input.vertices);
  return labels;
}

}  // namespace polycube
