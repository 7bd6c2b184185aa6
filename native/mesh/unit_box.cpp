#include "mesh/unit_box.h"

#include <cmath>

namespace polycube {
namespace {

// A mesh whose box centre is this close to the origin (relative to its
// size) and whose half-side is in (0.5, 1] counts as in the unit box
// already: moving it would only add rounding.
constexpr double kCentredEnough = 1.0 / (1 << 20);

}  // namespace

UnitBox::UnitBox(const PolygonMesh& mesh) {
  const Eigen::Index n = mesh.vertices.rows();
  if (mesh.faces.indices.empty()) return;
  Eigen::RowVector3d low = Eigen::RowVector3d::Constant(INFINITY), high = Eigen::RowVector3d::Constant(-INFINITY);
  for (int v : mesh.faces.indices) {
    if (v < 0 || v >= n || !mesh.vertices.row(v).allFinite()) return;
    low = low.cwiseMin(mesh.vertices.row(v));
    high = high.cwiseMax(mesh.vertices.row(v));
  }
  // Halves first: high - low itself can overflow near the largest double.
  centre_ = 0.5 * low + 0.5 * high;
  const double half_side = (0.5 * high - 0.5 * low).maxCoeff();
  if (!(half_side > 0.0) || !std::isfinite(half_side)) return;  // a single point: nothing to scale
  int exponent = 0;
  const double mantissa = std::frexp(half_side, &exponent);  // half_side = mantissa 2^exponent, mantissa in [0.5, 1)
  exponent_ = mantissa == 0.5 ? exponent - 1 : exponent;      // half_side / 2^exponent_ in (0.5, 1]
  identity_ = exponent_ == 0 && centre_.cwiseAbs().maxCoeff() <= kCentredEnough;
  if (identity_) centre_.setZero();
}

Vertices UnitBox::to_unit(const Vertices& positions) const {
  if (identity_) return positions;
  Vertices out(positions.rows(), 3);
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    for (int c = 0; c < 3; ++c)  // ldexp: exact, and no overflow in 2^-exponent itself
      out(v, c) = std::ldexp(positions(v, c), -exponent_) - std::ldexp(centre_[c], -exponent_);
  return out;
}

Vertices UnitBox::from_unit(const Vertices& unit_positions, const Vertices& unit_input, const Vertices& input) const {
  if (identity_) return unit_positions;
  Vertices out(unit_positions.rows(), 3);
  for (Eigen::Index v = 0; v < unit_positions.rows(); ++v) {
    if (v < unit_input.rows() && unit_positions.row(v) == unit_input.row(v)) {
      out.row(v) = input.row(v);
      continue;
    }
    for (int c = 0; c < 3; ++c) out(v, c) = std::ldexp(unit_positions(v, c), exponent_) + centre_[c];
  }
  return out;
}

UnitBoxMesh::UnitBoxMesh(const PolygonMesh& input) : input_(input), box_(input) {
  if (box_.identity()) return;
  moved_ = PolygonMesh{box_.to_unit(input.vertices), input.faces};
  // Vertices no face uses stay where they are whatever the core does; at the
  // origin they cannot overflow (one at 1e300 beside a model at 1e-300).
  std::vector<char> used(input.vertices.rows(), 0);
  for (int v : input.faces.indices) used[v] = 1;
  for (Eigen::Index v = 0; v < input.vertices.rows(); ++v)
    if (!used[v]) moved_->vertices.row(v).setZero();
}

}  // namespace polycube
