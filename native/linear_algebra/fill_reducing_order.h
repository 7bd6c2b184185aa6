// A fill-reducing elimination order of a symmetric sparsity pattern (a
// mesh's Laplacian: one row per vertex), the better of AMD's and METIS's,
// made by the first call and kept for the later ones.
//
// Why: systems whose unknowns follow a mesh's vertices (a few per vertex)
// factorise as sparsely in an order derived from the vertices' own as in
// one made for them, and at a million triangles making one costs about
// three factorisations (docs/design.md section 2.6, stage 7). Every run of
// one deform() has the same vertices, so one order serves them all.
#pragma once

#include <Eigen/SparseCore>
#include <vector>

namespace polycube {

class FillReducingOrder {
 public:
  // Per row of `pattern` (its lower triangle is read), its place in the
  // order: 0 is eliminated first. Later calls return the first call's,
  // whatever they pass.
  const std::vector<int>& rank(const Eigen::SparseMatrix<double>& pattern);

 private:
  std::vector<int> rank_;
  bool made_ = false;
};

}  // namespace polycube
