#include "labels/alpha_expansion.h"

#include <algorithm>

// GCC 12 warns about boost::optional inside Boost.Graph's edge iterators
// ("may be used uninitialized"): a known false positive in headers we do not own.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/graph/adjacency_list.hpp>
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>

namespace polycube {

double LabelEnergy::operator()(const std::vector<int>& labels) const {
  double e = 0.0;
  for (size_t i = 0; i < labels.size(); ++i) e += data(static_cast<Eigen::Index>(i), labels[i]);
  for (size_t k = 0; k < pairs.size(); ++k) e += weights[k] * label_cost(labels[pairs[k][0]], labels[pairs[k][1]]);
  return e;
}

namespace {

using Traits = boost::adjacency_list_traits<boost::vecS, boost::vecS, boost::directedS>;
using Graph = boost::adjacency_list<
    boost::vecS, boost::vecS, boost::directedS,
    boost::property<boost::vertex_index_t, long,
                    boost::property<boost::vertex_color_t, boost::default_color_type,
                                    boost::property<boost::vertex_distance_t, long,
                                                    boost::property<boost::vertex_predecessor_t,
                                                                    Traits::edge_descriptor>>>>,
    boost::property<boost::edge_capacity_t, double,
                    boost::property<boost::edge_residual_capacity_t, double,
                                    boost::property<boost::edge_reverse_t, Traits::edge_descriptor>>>>;

// A directed edge u -> v with capacity c and its zero-capacity reverse, as
// Boost's max-flow wants every edge paired.
void add_arc(Graph& g, long u, long v, double c) {
  const auto forward = boost::add_edge(u, v, g).first;
  const auto backward = boost::add_edge(v, u, g).first;
  boost::put(boost::edge_capacity, g, forward, c);
  boost::put(boost::edge_capacity, g, backward, 0.0);
  boost::put(boost::edge_reverse, g, forward, backward);
  boost::put(boost::edge_reverse, g, backward, forward);
}

// One expansion move: x_i = 0 keeps the label, x_i = 1 takes alpha. Site i on
// the source side of the cut keeps its label.
std::vector<int> expand(const LabelEnergy& energy, const std::vector<int>& labels, int alpha) {
  const long n = static_cast<long>(labels.size()), source = n, sink = n + 1;
  Graph g(n + 2);
  // unary[i] = cost(x_i = 1) - cost(x_i = 0), collected before the t-links.
  std::vector<double> unary(n);
  for (long i = 0; i < n; ++i) unary[i] = energy.data(i, alpha) - energy.data(i, labels[i]);
  for (size_t k = 0; k < energy.pairs.size(); ++k) {
    const int i = energy.pairs[k][0], j = energy.pairs[k][1];
    const double w = energy.weights[k];
    const double b = w * energy.label_cost(labels[i], alpha);  // E(0,1)
    const double c = w * energy.label_cost(alpha, labels[j]);  // E(1,0)
    // E(0,0) lowered where needed so the term is submodular (see the header);
    // E(1,1) = 0.
    const double a = std::min(w * energy.label_cost(labels[i], labels[j]), b + c);
    // E = a + (c - a) x_i + (0 - c) x_j + (b + c - a) (1 - x_i) x_j
    unary[i] += c - a;
    unary[j] -= c;
    const double cut = b + c - a;
    if (cut > 0.0) add_arc(g, i, j, cut);  // cut when i keeps (source) and j takes alpha (sink)
  }
  for (long i = 0; i < n; ++i) {
    if (unary[i] > 0.0) add_arc(g, source, i, unary[i]);  // cut when i takes alpha
    else if (unary[i] < 0.0) add_arc(g, i, sink, -unary[i]);  // cut when i keeps its label
  }
  boost::boykov_kolmogorov_max_flow(g, source, sink);
  std::vector<int> result = labels;
  const auto color = boost::get(boost::vertex_color, g);
  for (long i = 0; i < n; ++i)
    if (boost::get(color, i) != boost::black_color) result[i] = alpha;
  return result;
}

}  // namespace

std::vector<int> alpha_expansion(const LabelEnergy& energy, std::vector<int> labels, int max_cycles) {
  const int label_count = static_cast<int>(energy.data.cols());
  double current = energy(labels);
  for (int cycle = 0; cycle < max_cycles; ++cycle) {
    bool improved = false;
    for (int alpha = 0; alpha < label_count; ++alpha) {
      std::vector<int> candidate = expand(energy, labels, alpha);
      const double value = energy(candidate);
      // A relative margin: float noise in the flow must not count as progress.
      if (value < current - 1e-9 * std::max(1.0, std::abs(current))) {
        labels = std::move(candidate);
        current = value;
        improved = true;
      }
    }
    if (!improved) break;
  }
  return labels;
}

}  // namespace polycube
