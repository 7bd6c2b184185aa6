#include "labels/auto_labels.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "labels/alpha_expansion.h"
#include "labels/axis.h"
#include "mesh/check_input.h"
#include "mesh/mesh_adjacency.h"
#include "labels/repair_charts.h"
#include "mesh/triangulate.h"

namespace polycube {
namespace {

// Fidelity of a unit normal to a label axis, 0 when they agree, close to 1
// from about 50 degrees on: the Gaussian falloff of PolyCut (Livesu et al.
// 2013), so a face has little preference between the labels it clearly is
// not. Beyond 90 degrees it rises again: a face whose label points away from
// it must fold, so the repair moves (which compare energies) avoid that.
double fidelity_cost(const Eigen::Vector3d& normal, int label) {
  constexpr double kSigma = 0.2, kAgainst = 2.0;
  const double dot = normal.dot(label_axis(label)), x = (dot - 1.0) / kSigma;
  return 1.0 - std::exp(-0.5 * x * x) + kAgainst * std::max(0.0, -dot);
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

LabelEnergy label_energy(const PolygonMesh& mesh, const MeshAdjacency& adjacency, double compactness) {
  const int face_count = mesh.faces.count();
  std::vector<Eigen::Vector3d> normals(face_count);
  std::vector<double> areas(face_count);
  double total_area = 0.0;
  for (int f = 0; f < face_count; ++f) {
    const Eigen::Vector3d n = newell_normal(mesh.vertices, mesh.faces, f);
    areas[f] = 0.5 * n.norm();
    normals[f] = areas[f] > 0.0 ? Eigen::Vector3d(n / n.norm()) : Eigen::Vector3d::Zero();
    total_area += areas[f];
  }
  // Costs in units of the mean face area, so the numbers stay near 1.
  const double mean_area = total_area > 0.0 ? total_area / face_count : 1.0;
  LabelEnergy energy;
  energy.data.resize(face_count, 6);
  for (int f = 0; f < face_count; ++f)
    for (int l = 0; l < 6; ++l) energy.data(f, l) = areas[f] / mean_area * fidelity_cost(normals[f], l);
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

std::vector<int> auto_labels(const PolygonMesh& mesh, const AutoLabelOptions& options) {
  check_input(mesh);
  if (!(options.compactness >= 0.0) || !std::isfinite(options.compactness))
    throw Error("compactness must be a finite number of at least 0");
  const MeshAdjacency adjacency = mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows()));
  const LabelEnergy energy = label_energy(mesh, adjacency, options.compactness);
  std::vector<int> labels(mesh.faces.count());
  for (int f = 0; f < mesh.faces.count(); ++f) {
    int best = 0;
    for (int l = 1; l < 6; ++l)
      if (energy.data(f, l) < energy.data(f, best)) best = l;
    labels[f] = best;  // the nearest axis (lowest label on ties)
  }
  labels = alpha_expansion(energy, std::move(labels));
  if (options.repair) {
    std::vector<double> areas(mesh.faces.count());
    for (int f = 0; f < mesh.faces.count(); ++f) areas[f] = 0.5 * newell_normal(mesh.vertices, mesh.faces, f).norm();
    labels = merge_tiny_charts(adjacency, energy, areas, std::move(labels), options.repair_moves);
    labels = repair_charts(adjacency, energy, std::move(labels), options.repair_moves);
    labels = merge_tiny_charts(adjacency, energy, areas, std::move(labels), options.repair_moves);
  }
  return labels;
}

}  // namespace polycube
