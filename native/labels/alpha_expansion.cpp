#include "labels/alpha_expansion.h"

#include <algorithm>

// GCC 12 warns about boost::optional inside Boost.Graph's edge iterators
// ("may be used uninitialized"): a known false positive in headers we do not own.
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <boost/graph/boykov_kolmogorov_max_flow.hpp>
#include <boost/graph/compressed_sparse_row_graph.hpp>

namespace polycube {

double LabelEnergy::operator()(const std::vector<int>& labels) const {
  double e = 0.0;
  for (size_t i = 0; i < labels.size(); ++i) e += data(static_cast<Eigen::Index>(i), labels[i]);
  for (size_t k = 0; k < pairs.size(); ++k) e += weights[k] * label_cost(labels[pairs[k][0]], labels[pairs[k][1]]);
  return e;
}

namespace {

// The flow graph of one expansion move in compressed rows: a few arrays,
// where an adjacency list allocated every edge's properties on its own and
// building it was as much of the labeller's time as the max-flow (bunny00
// refined to 300,000 faces). The arrays are kept between the moves of one
// alpha_expansion call.
using Graph = boost::compressed_sparse_row_graph<boost::directedS>;
using Vertex = boost::graph_traits<Graph>::vertex_descriptor;
using Edge = boost::graph_traits<Graph>::edge_descriptor;

struct FlowGraph {
  // Arcs as added: edge 2k is u -> v with capacity c, edge 2k + 1 its
  // zero-capacity reverse, as Boost's max-flow wants every edge paired.
  std::vector<Vertex> from, to;
  std::vector<double> capacity;
  // The same edges in rows (by their first vertex, in the order added, the
  // order an adjacency list walks them, so the max-flow augments the same
  // paths in the same order and cuts the same faces, bit for bit).
  std::vector<std::pair<Vertex, Vertex>> rows;
  std::vector<size_t> row_of, next;
  std::vector<double> row_capacity, residual;
  std::vector<Edge> reverse, predecessor;
  std::vector<boost::default_color_type> color;
  std::vector<long> distance;

  void clear() {
    from.clear();
    to.clear();
    capacity.clear();
  }
  void add_arc(Vertex u, Vertex v, double c) {
    from.push_back(u), to.push_back(v), capacity.push_back(c);
    from.push_back(v), to.push_back(u), capacity.push_back(0.0);
  }
  // The max-flow from `source` to `sink`; afterwards color[i] is black for
  // the vertices on the source side of the cut.
  void cut(Vertex vertex_count, Vertex source, Vertex sink);
};

void FlowGraph::cut(Vertex vertex_count, Vertex source, Vertex sink) {
  const size_t edge_count = from.size();
  next.assign(vertex_count + 1, 0);
  for (Vertex u : from) ++next[u + 1];
  for (Vertex v = 0; v < vertex_count; ++v) next[v + 1] += next[v];
  row_of.resize(edge_count);
  for (size_t e = 0; e < edge_count; ++e) row_of[e] = next[from[e]]++;
  rows.resize(edge_count);
  row_capacity.resize(edge_count);
  reverse.resize(edge_count);
  for (size_t e = 0; e < edge_count; ++e) {
    rows[row_of[e]] = {from[e], to[e]};
    row_capacity[row_of[e]] = capacity[e];
    reverse[row_of[e]] = Edge(to[e], row_of[e ^ 1]);
  }
  const Graph g(boost::edges_are_sorted, rows.begin(), rows.end(), vertex_count, edge_count);
  residual.resize(edge_count);
  predecessor.resize(vertex_count);
  color.resize(vertex_count);
  distance.assign(vertex_count, 0);
  const auto edge_index = boost::get(boost::edge_index, g);
  const auto vertex_index = boost::get(boost::vertex_index, g);
  boost::boykov_kolmogorov_max_flow(g, boost::make_iterator_property_map(row_capacity.begin(), edge_index),
                                    boost::make_iterator_property_map(residual.begin(), edge_index),
                                    boost::make_iterator_property_map(reverse.begin(), edge_index),
                                    boost::make_iterator_property_map(predecessor.begin(), vertex_index),
                                    boost::make_iterator_property_map(color.begin(), vertex_index),
                                    boost::make_iterator_property_map(distance.begin(), vertex_index), vertex_index,
                                    source, sink);
}

// One expansion move: x_i = 0 keeps the label, x_i = 1 takes alpha. Site i on
// the source side of the cut keeps its label.
std::vector<int> expand(const LabelEnergy& energy, const std::vector<int>& labels, int alpha, FlowGraph& g,
                        std::vector<double>& unary) {
  const long n = static_cast<long>(labels.size()), source = n, sink = n + 1;
  g.clear();
  // unary[i] = cost(x_i = 1) - cost(x_i = 0), collected before the t-links.
  unary.resize(n);
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
    if (cut > 0.0) g.add_arc(i, j, cut);  // cut when i keeps (source) and j takes alpha (sink)
  }
  for (long i = 0; i < n; ++i) {
    if (unary[i] > 0.0)
      g.add_arc(source, i, unary[i]);  // cut when i takes alpha
    else if (unary[i] < 0.0)
      g.add_arc(i, sink, -unary[i]);  // cut when i keeps its label
  }
  g.cut(n + 2, source, sink);
  std::vector<int> result = labels;
  for (long i = 0; i < n; ++i)
    if (g.color[i] != boost::black_color) result[i] = alpha;
  return result;
}

}  // namespace

std::vector<int> alpha_expansion(const LabelEnergy& energy, std::vector<int> labels, int max_cycles) {
  const int label_count = static_cast<int>(energy.data.cols());
  double current = energy(labels);
  FlowGraph graph;
  std::vector<double> unary;
  for (int cycle = 0; cycle < max_cycles; ++cycle) {
    bool improved = false;
    for (int alpha = 0; alpha < label_count; ++alpha) {
      std::vector<int> candidate = expand(energy, labels, alpha, graph, unary);
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
