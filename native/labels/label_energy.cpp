#include "labels/label_energy.h"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "labels/axis.h"
#include "mesh/triangulate.h"

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

}  // namespace

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

}  // namespace polycube
