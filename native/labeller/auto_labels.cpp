#include "labeller/auto_labels.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "labels/alpha_expansion.h"
#include "labels/axis.h"
#include "mesh/check_input.h"
#include "mesh/mesh_adjacency.h"
#include "labels/faces_facing_away.h"
#include "labels/open_caps.h"
#include "labels/repair_charts.h"
#include "labels/squeezed_triangles.h"
#include "labeller/straighten.h"
#include "mesh/triangulate.h"
#include "mesh/unit_box.h"

namespace polycube {
namespace {

// Fidelity of a unit normal to a label axis, 0 when they agree, close to 1
// from about 50 degrees on: the Gaussian falloff of PolyCut (Livesu et al.
// 2013), so a face has little preference between the labels it clearly is
// not. Beyond 90 degrees it rises again: a face whose label points away from
// it must fold, so the repair moves (which compare energies) avoid that.
constexpr double kAgainst = 2.0;
double fidelity_cost(const Eigen::Vector3d& normal, int label) {
  constexpr double kSigma = 0.2;
  const double dot = normal.dot(label_axis(label)), x = (dot - 1.0) / kSigma;
  return 1.0 - std::exp(-0.5 * x * x) + kAgainst * std::max(0.0, -dot);
}

// The straightened shape turns whole parts (a curled trunk unrolls), so a
// label that fits its normal can point away from the input's; the
// deformation would have to turn such faces over. The same penalty as above,
// on the input's normal, keeps charts from pointing away from their axes.
double against_input_cost(const Eigen::Vector3d& input_normal, int label) {
  return kAgainst * std::max(0.0, -input_normal.dot(label_axis(label)));
}

// Chart boundaries along creases are what a user expects (fandisk's sharp
// edges), so they cost less: the weight falls off with the angle between the
// two face normals, down to a floor so boundaries still stay short there.
double crease_factor(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  constexpr double kAngle = 40.0 * M_PI / 180.0, kFloor = 0.05;
  const double angle = std::acos(std::clamp(a.dot(b), -1.0, 1.0)) / kAngle;
  return std::max(kFloor, std::exp(-angle * angle));
}

// Opposite labels side by side cannot become a polycube: they cost this much
// more than orthogonal ones (not a metric; alpha_expansion copes).
constexpr double kOppositeCost = 4.0;
// h of the header as a share of sqrt(surface area).
constexpr double kLengthScale = 0.01;

// mesh: the straightened shape, whose normals the labels follow; input: the
// input's positions, for the faces' areas and the against-input term.
LabelEnergy label_energy(const PolygonMesh& mesh, const Vertices& input, const MeshAdjacency& adjacency,
                         double compactness) {
  const int face_count = mesh.faces.count();
  std::vector<Eigen::Vector3d> normals(face_count), input_normals(face_count);
  std::vector<double> areas(face_count);
  double total_area = 0.0;
  for (int f = 0; f < face_count; ++f) {
    const Eigen::Vector3d n = newell_normal(mesh.vertices, mesh.faces, f);
    normals[f] = n.norm() > 0.0 ? Eigen::Vector3d(n / n.norm()) : Eigen::Vector3d::Zero();
    const Eigen::Vector3d m = newell_normal(input, mesh.faces, f);
    areas[f] = 0.5 * m.norm();
    input_normals[f] = areas[f] > 0.0 ? Eigen::Vector3d(m / m.norm()) : Eigen::Vector3d::Zero();
    total_area += areas[f];
  }
  // Costs in units of the mean face area, so the numbers stay near 1.
  const double mean_area = total_area > 0.0 ? total_area / face_count : 1.0;
  LabelEnergy energy;
  energy.data.resize(face_count, 6);
  for (int f = 0; f < face_count; ++f)
    for (int l = 0; l < 6; ++l)
      energy.data(f, l) =
          areas[f] / mean_area * (fidelity_cost(normals[f], l) + against_input_cost(input_normals[f], l));
  const double h = kLengthScale * std::sqrt(total_area);
  for (int e = 0; e < adjacency.edge_count(); ++e) {
    const Eigen::Vector3d p = mesh.vertices.row(adjacency.edges[e][0]), q = mesh.vertices.row(adjacency.edges[e][1]);
    const double length = (p - q).norm();
    for (int i = adjacency.edge_offsets[e]; i < adjacency.edge_offsets[e + 1]; ++i)
      for (int j = i + 1; j < adjacency.edge_offsets[e + 1]; ++j) {
        const int a = adjacency.edge_faces[i], b = adjacency.edge_faces[j];
        if (a == b) continue;
        energy.pairs.push_back({a, b});
        energy.weights.push_back(compactness * length * h / mean_area * crease_factor(normals[a], normals[b]));
      }
  }
  energy.label_cost.setOnes(6, 6);
  for (int l = 0; l < 6; ++l) {
    energy.label_cost(l, l) = 0.0;
    energy.label_cost(l, l ^ 1) = kOppositeCost;
  }
  return energy;
}

}  // namespace

AutoLabelOptions AutoLabelOptions::with_detail(double detail) {
  if (!(detail >= 0.0 && detail <= 1.0)) throw Error("detail must be a number from 0 to 1");
  AutoLabelOptions options;
  options.compactness = 0.3 * std::pow(10.0, 1.0 - 2.0 * detail);
  options.straighten_rings = std::max(1, static_cast<int>(std::lround(3.0 * std::pow(4.0, 1.0 - 2.0 * detail))));
  // Merging away small charts makes the coarse end of the knob what a user
  // asks for there (Suzanne at 0: 12 charts, a head and its muzzle), but it
  // loses limbs on organic models (the elephant's legs) and collapses more
  // there, so the default keeps every chart the cut and the repair found.
  options.simplify_below = std::max(0.0, 0.01 * (1.0 - 2.0 * detail));
  return options;
}

std::vector<int> auto_labels(const PolygonMesh& input, const AutoLabelOptions& options, Vertices* straightened) {
  const UnitBoxMesh unit(input);  // scale independence (unit_box.h); `straightened` goes back below
  const PolygonMesh& mesh = unit.mesh();
  check_input(mesh);
  if (!(options.compactness >= 0.0) || !std::isfinite(options.compactness))
    throw Error("compactness must be a finite number of at least 0");
  const int vertex_count = static_cast<int>(mesh.vertices.rows());
  const MeshAdjacency adjacency = mesh_adjacency(mesh.faces, vertex_count);
  const Triangulation triangulation = triangulate(mesh.vertices, mesh.faces);
  StraightenOptions so{options.straighten_iterations, options.straighten_rings};
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
  std::vector<double> areas(mesh.faces.count());
  for (int f = 0; f < mesh.faces.count(); ++f) areas[f] = 0.5 * newell_normal(mesh.vertices, mesh.faces, f).norm();
  if (options.repair) {
    labels = merge_tiny_charts(adjacency, energy, areas, std::move(labels), options.repair_moves);
    labels = repair_charts(adjacency, energy, std::move(labels), options.repair_moves);
    labels = merge_tiny_charts(adjacency, energy, areas, std::move(labels), options.repair_moves);
    // Faces facing away from their labels, then what relabelling them broke.
    if (relabel_faces_facing_away(mesh, face_neighbours(adjacency, mesh.faces.count()), labels) > 0) {
      labels = repair_charts(adjacency, energy, std::move(labels), options.repair_moves);
      labels = merge_tiny_charts(adjacency, energy, areas, std::move(labels), options.repair_moves);
    }
    // Squeezed triangles, then what relabelling them broke; a few rounds,
    // as each repair can leave new teeth. Kept only when the polycube
    // conditions hold as well as before.
    const int violations = violation_score(adjacency, labels);
    std::vector<int> unsqueezed = labels;
    for (int round = 0; round < 3; ++round) {
      if (unsqueeze_labels(vertex_count, triangulation.triangles, triangulation.face_of_triangle, unsqueezed) == 0)
        break;
      unsqueezed = repair_charts(adjacency, energy, std::move(unsqueezed), options.repair_moves);
      unsqueezed = merge_tiny_charts(adjacency, energy, areas, std::move(unsqueezed), options.repair_moves);
    }
    if (violation_score(adjacency, unsqueezed) <= violations) labels = std::move(unsqueezed);
  }
  label_open_caps(mesh, adjacency, labels);
  if (options.repair && options.simplify_below > 0.0)
    labels = simplify_charts(adjacency, energy, areas, std::move(labels), options.simplify_below, options.repair_moves);
  if (straightened) *straightened = unit.box().from_unit(straight.vertices, mesh.vertices, input.vertices);
  return labels;
}

}  // namespace polycube
