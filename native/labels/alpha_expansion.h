// Multi-label energy minimisation by alpha-expansion (Boykov, Veksler, Zabih
// 2001): for each label alpha in turn, one s-t minimum cut (Boost.Graph's
// Boykov-Kolmogorov max-flow) finds the best way to switch any set of sites
// to alpha; repeat until no switch lowers the energy.
//
//   E(l) = sum_i data(i, l_i) + sum_{(i,j)} weight_ij * label_cost(l_i, l_j)
//
// label_cost must be symmetric with a zero diagonal. Where it is a metric the
// moves are exact; where it is not (a large cost between two labels), the
// move's pairwise term is lowered until submodular and a move is kept only if
// the true energy goes down, so the energy never rises either way.
#pragma once

#include <Eigen/Core>
#include <array>
#include <vector>

namespace polycube {

struct LabelEnergy {
  Eigen::MatrixXd data;                     // sites x labels, >= 0
  std::vector<std::array<int, 2>> pairs;    // neighbouring sites
  std::vector<double> weights;              // per pair, >= 0
  Eigen::MatrixXd label_cost;               // labels x labels

  double operator()(const std::vector<int>& labels) const;
};

// Starts from `labels` (one per site, 0..labels-1) and returns the labeling
// after at most max_cycles sweeps over the labels. Deterministic.
std::vector<int> alpha_expansion(const LabelEnergy& energy, std::vector<int> labels, int max_cycles = 8);

}  // namespace polycube
