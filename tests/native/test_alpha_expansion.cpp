// alpha_expansion (labels/alpha_expansion.h): each expansion move is a
// minimum cut, so where the label costs are a metric the result is a local
// minimum for every move: no set of sites switched to one label lowers the
// energy. Checked by enumerating all such moves on small grids, which fails
// if the flow graph loses, swaps or misdirects an edge.
#include <gtest/gtest.h>

#include <random>

#include "labels/alpha_expansion.h"

namespace polycube {
namespace {

// A rows x cols grid of sites with random data costs and pair weights;
// label costs 1 between distinct labels (a metric).
LabelEnergy random_grid(int rows, int cols, int labels, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  LabelEnergy energy;
  energy.data.resize(rows * cols, labels);
  for (int i = 0; i < rows * cols; ++i)
    for (int l = 0; l < labels; ++l) energy.data(i, l) = unit(random);
  for (int r = 0; r < rows; ++r)
    for (int c = 0; c < cols; ++c) {
      const int i = r * cols + c;
      if (c + 1 < cols) energy.pairs.push_back({i, i + 1}), energy.weights.push_back(0.6 * unit(random));
      if (r + 1 < rows) energy.pairs.push_back({i, i + cols}), energy.weights.push_back(0.6 * unit(random));
    }
  energy.label_cost = Eigen::MatrixXd::Ones(labels, labels) - Eigen::MatrixXd::Identity(labels, labels);
  return energy;
}

TEST(AlphaExpansion, NoExpansionMoveLowersTheResult) {
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const LabelEnergy energy = random_grid(3, 4, 3, seed);
    const int sites = static_cast<int>(energy.data.rows());
    std::vector<int> start(sites, 0);
    const std::vector<int> labels = alpha_expansion(energy, start);
    const double value = energy(labels);
    EXPECT_LE(value, energy(start) + 1e-12) << "seed " << seed;
    for (int alpha = 0; alpha < 3; ++alpha)
      for (int subset = 1; subset < (1 << sites); ++subset) {
        std::vector<int> moved = labels;
        for (int i = 0; i < sites; ++i)
          if (subset >> i & 1) moved[i] = alpha;
        ASSERT_GE(energy(moved), value - 1e-9) << "seed " << seed << ", alpha " << alpha << ", sites " << subset;
      }
  }
}

// A move that does not lower the energy is not taken: the labels already at
// the minimum come back unchanged.
TEST(AlphaExpansion, KeepsAMinimum) {
  const LabelEnergy energy = random_grid(4, 4, 4, 7);
  const std::vector<int> once = alpha_expansion(energy, std::vector<int>(16, 1));
  EXPECT_EQ(alpha_expansion(energy, once), once);
}

}  // namespace
}  // namespace polycube
