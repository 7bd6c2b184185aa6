// Unconstrained minimisation by limited-memory BFGS (Nocedal and Wright,
// Numerical Optimization, algorithm 7.5) with a backtracking line search on
// the Armijo condition.
//
// Why our own: the energies minimised here (deform/untangle_flat_charts.h) are
// smooth everywhere, their gradients cost one pass over the mesh, and a few
// hundred iterations from a good start are all they need; Debian's Eigen has
// no such solver and the extra package would be the only use of it.
#pragma once

#include <Eigen/Core>
#include <functional>

namespace polycube {

// Returns f(x) and writes its gradient into `gradient` (sized like x).
using Objective = std::function<double(const Eigen::VectorXd& x, Eigen::VectorXd& gradient)>;

struct LbfgsResult {
  int iterations = 0;
  double value = 0.0;
  bool converged = false;  // the gradient or the decrease fell below the tolerance
  bool stopped = false;    // `stop` answered true
};

// `stop` is polled before the first iteration and then at most this often:
// a round of a million-triangle untangling takes seconds, and a stop that
// calls into Python (the add-on's Esc) costs more than an iteration of a
// small mesh.
constexpr double kLbfgsStopPollSeconds = 0.1;
// The (s, y) pairs kept, by default.
constexpr int kLbfgsMemory = 7;

// Minimises from `x` in place. Stops after `max_iterations`, when the largest
// gradient entry is below `gradient_tolerance`, when an iteration lowers f
// by less than `relative_tolerance` of |f|, or when `stop` (if given)
// answers true: `x` is then the last iterate.
LbfgsResult minimize_lbfgs(const Objective& objective, Eigen::VectorXd& x, int max_iterations,
                           double gradient_tolerance = 1e-10, double relative_tolerance = 1e-10,
                           int memory = kLbfgsMemory, const std::function<bool()>& stop = {});

}  // namespace polycube
