// Minimisation by Newton's method of an energy that is a sum over elements,
// each depending on a few unknowns (a triangle's corners), with every
// element's Hessian made positive semi-definite by the energy (projected
// Newton, as in Teran et al. 2005), a sparse Cholesky solve per iteration and
// a backtracking line search on the Armijo condition.
//
// Why: where L-BFGS needs hundreds of gradient passes per minimisation
// (deform/untangle_flat_charts.h), the per-element Hessians are cheap and the
// assembled system is mesh-like, so a handful of factorisations reach the
// minimum. The sparsity pattern, its symbolic analysis and where each
// element's entries go are kept while the elements stay the same, so a
// minimiser called again on the same elements (the next eps of the
// untangling) only factorises.
#pragma once

#include <Eigen/Core>
#include <functional>
#include <memory>
#include <vector>

namespace polycube {

// Takes the Hessians of elements first .. first + count - 1: each element's
// K x K Hessian in its K unknowns, positive semi-definite, column-major, K * K
// numbers per element. The minimiser adds them into its system as they come,
// so an objective hands them over in blocks of its choice, in element order,
// and never holds all of them (a million triangles: 290 MB beside the factor).
using HessianSink = std::function<void(size_t first, size_t count, const double* hessians)>;
// Returns f(x). When `gradient` is not null, writes the gradient into it
// (sized like x). When `hessians` is not null, gives it every element's
// Hessian, each element once, in element order. f may be +infinity where
// undefined.
using ElementObjective =
    std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd* gradient, const HessianSink* hessians)>;

struct NewtonResult {
  int iterations = 0;
  int factorizations = 0;
  double value = 0.0;
  bool converged = false;  // the gradient, the decrease or the predicted decrease fell below the tolerance
  bool stopped = false;    // `stop` answered true before an iteration
};

class NewtonMinimizer {
 public:
  NewtonMinimizer();
  ~NewtonMinimizer();

  // Minimises from `x` in place over its first `free` entries (the others
  // held). `element_unknowns`: K entries of x per element, repeats allowed
  // (an unknown shared by two corners). Stops after `max_iterations`, when
  // the largest free gradient entry is below `gradient_tolerance`, or when an
  // iteration lowers f (or Newton's model predicts it would) by less than
  // `relative_tolerance` of |f|. `stop`, when given, is asked before every
  // iteration (each a factorisation: seconds at a million triangles) and
  // ends the minimisation, `x` as the last iteration left it, when true.
  NewtonResult minimize(const ElementObjective& objective, const std::vector<int>& element_unknowns, int element_size,
                        int free, Eigen::VectorXd& x, int max_iterations, double gradient_tolerance = 1e-10,
                        double relative_tolerance = 1e-10, const std::function<bool()>& stop = {});

  // Per free unknown of the last system, the place at which its
  // factorisation eliminates it (empty before the first minimize()).
  std::vector<int> places() const;
  // The next system that is not the last one is ordered by `keys` (one per
  // free unknown, the lowest eliminated first, ties in the unknowns' order)
  // instead of by a fill-reducing ordering of its own, when their sizes
  // agree and its factor is not much larger than the last system's
  // (minimize_newton.cpp). For a system that is the last one with some of its unknowns
  // joined: each joined unknown keyed by the latest place of those it
  // joins keeps the last ordering's fill, where ordering it afresh costs
  // as much as several factorisations (docs/design.md section 2.6, stage 7).
  void order_next_by(std::vector<int> keys);

 private:
  struct System;
  std::unique_ptr<System> system_;
  std::vector<int> next_keys_;
};

}  // namespace polycube
