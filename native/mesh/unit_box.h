// Scale independence: the core works on the mesh moved and scaled into the
// unit box, so results and figures do not depend on the unit the model was
// made in (millimetres or kilometres, 1e-150 or 1e150). Squared lengths and
// cross products of raw coordinates overflow above about 1e77 and underflow
// below about 1e-100; in the unit box they never do, and absolute
// thresholds inside the solver mean the same thing on every model.
//
// The map is x -> (x - centre) * 2^-exponent: the centre of the bounding box
// of the vertices the faces use goes to the origin, its largest half-side to
// (0.5, 1]. A power of two scales without rounding, so a model and the same
// model at another scale differ in the unit box only by the rounding their
// own coordinates had.
//
// Each public entry of the core (deform, auto_labels, validate_labels,
// nearest_labels, orientation) starts with
//   const UnitBoxMesh unit(input);
//   const PolygonMesh& mesh = unit.mesh();
// and deform maps its positions back with UnitBox::from_unit.
#pragma once

#include <optional>

#include "mesh/mesh.h"

namespace polycube {

class UnitBox {
 public:
  // The box of the vertices mesh.faces use. Identity when the mesh is
  // already in the unit box (then nothing is copied or changed), and when it
  // is not a mesh the core takes (no faces, an index out of range, a
  // non-finite coordinate): the entry's own check_input says what is wrong.
  explicit UnitBox(const PolygonMesh& mesh);

  bool identity() const { return identity_; }
  // Every row mapped, unreferenced vertices too.
  Vertices to_unit(const Vertices& positions) const;
  // The inverse. Rows equal to unit_input's come back as input's exactly, so
  // vertices the core did not move keep their coordinates to the bit.
  Vertices from_unit(const Vertices& unit_positions, const Vertices& unit_input, const Vertices& input) const;

 private:
  Eigen::RowVector3d centre_ = Eigen::RowVector3d::Zero();
  int exponent_ = 0;
  bool identity_ = true;
};

// The mesh in the unit box: a copy when it had to move, the input itself
// when it was there already. Keep it alive while mesh() is used.
class UnitBoxMesh {
 public:
  explicit UnitBoxMesh(const PolygonMesh& input);
  const PolygonMesh& mesh() const { return moved_ ? *moved_ : input_; }
  const UnitBox& box() const { return box_; }

 private:
  const PolygonMesh& input_;
  UnitBox box_;
  std::optional<PolygonMesh> moved_;
};

}  // namespace polycube
