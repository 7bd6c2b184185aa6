// The line search both minimisers use (minimize_lbfgs.h, minimize_newton.h):
// from step length `first`, halve until f(t) falls by at least 1e-4 of what
// the slope promises (Armijo's condition), at most 40 times.
#pragma once

#include <cmath>

namespace polycube {

// `value_at(t)`: f at step length t along the direction (the caller keeps
// the point it evaluated, and its gradient if it wants it). `value`: f at
// t = 0; `slope`: its derivative along the direction (negative). Returns the
// accepted t and writes its f into `accepted_value`, or returns 0 when no
// halving decreased f enough (no decrease left at this precision).
template <typename ValueAt>
double armijo_backtracking(ValueAt&& value_at, double value, double slope, double first, double& accepted_value) {
  double t = first;
  for (int halving = 0; halving < 40; ++halving, t *= 0.5) {
    accepted_value = value_at(t);
    if (std::isfinite(accepted_value) && accepted_value <= value + 1e-4 * t * slope) return t;
  }
  return 0.0;
}

}  // namespace polycube
