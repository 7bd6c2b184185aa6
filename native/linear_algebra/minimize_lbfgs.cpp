#include "linear_algebra/minimize_lbfgs.h"

#include <chrono>
#include <cmath>
#include <deque>
#include <vector>

#include "linear_algebra/armijo_backtracking.h"

namespace polycube {

LbfgsResult minimize_lbfgs(const Objective& objective, Eigen::VectorXd& x, int max_iterations,
                           double gradient_tolerance, double relative_tolerance, int memory,
                           const std::function<bool()>& stop) {
  using Clock = std::chrono::steady_clock;
  LbfgsResult result;
  Clock::time_point polled;
  Eigen::VectorXd gradient(x.size()), next_gradient(x.size());
  double value = objective(x, gradient);
  std::deque<Eigen::VectorXd> steps, changes;  // s_k and y_k, newest last
  std::deque<double> rho;
  std::vector<double> alpha(memory);
  for (; result.iterations < max_iterations; ++result.iterations) {
    if (stop && (result.iterations == 0 ||
                 std::chrono::duration<double>(Clock::now() - polled).count() >= kLbfgsStopPollSeconds)) {
      if (stop()) {
        result.stopped = true;
        break;
      }
      polled = Clock::now();
    }
    if (!std::isfinite(value) || gradient.lpNorm<Eigen::Infinity>() < gradient_tolerance) {
      result.converged = std::isfinite(value);
      break;
    }
    // Two-loop recursion: direction = -H gradient.
    Eigen::VectorXd direction = -gradient;
    for (int i = static_cast<int>(steps.size()) - 1; i >= 0; --i) {
      alpha[i] = rho[i] * steps[i].dot(direction);
      direction -= alpha[i] * changes[i];
    }
    if (!steps.empty()) direction *= steps.back().dot(changes.back()) / changes.back().squaredNorm();
    for (size_t i = 0; i < steps.size(); ++i) {
      const double beta = rho[i] * changes[i].dot(direction);
      direction += (alpha[i] - beta) * steps[i];
    }
    double slope = gradient.dot(direction);
    if (!(slope < 0.0)) {  // not a descent direction: restart from the gradient
      steps.clear(), changes.clear(), rho.clear();
      direction = -gradient;
      slope = -gradient.squaredNorm();
    }
    // The first step has no curvature yet: keep it short.
    const double first = steps.empty() ? std::min(1.0, 1.0 / gradient.lpNorm<Eigen::Infinity>()) : 1.0;
    Eigen::VectorXd next;
    double next_value = value;
    const auto value_at = [&](double t) {
      next = x + t * direction;
      return objective(next, next_gradient);
    };
    if (armijo_backtracking(value_at, value, slope, first, next_value) == 0.0) {
      result.converged = true;  // no decrease left at this precision
      break;
    }
    const double decrease = value - next_value;
    Eigen::VectorXd s = next - x, y = next_gradient - gradient;
    x = std::move(next);
    gradient.swap(next_gradient);
    value = next_value;
    const double curvature = s.dot(y);
    if (curvature > 1e-16 * s.norm() * y.norm()) {
      if (static_cast<int>(steps.size()) == memory) steps.pop_front(), changes.pop_front(), rho.pop_front();
      steps.push_back(std::move(s));
      changes.push_back(std::move(y));
      rho.push_back(1.0 / curvature);
    }
    if (decrease <= relative_tolerance * std::abs(value)) {
      result.converged = true;
      ++result.iterations;
      break;
    }
  }
  result.value = value;
  return result;
}

}  // namespace polycube
