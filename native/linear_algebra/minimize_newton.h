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

 private:
  struct System;
  std::unique_ptr<System> system_;
};

}  // namespace polycube
