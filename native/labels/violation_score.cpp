#include "labels/violation_score.h"

#include <algorithm>
#include <cstdint>

#include "mesh/union_find.h"

namespace polycube {
namespace {

std::uint64_t pair_key(int a, int b) {
  return static_cast<std::uint64_t>(std::min(a, b)) << 32 | static_cast<std::uint32_t>(std::max(a, b));
}

int missing_neighbours(size_t neighbours) { return std::max(0, 4 - static_cast<int>(neighbours)); }

// Charts beyond three among `ids` (a vertex's faces' charts). A vertex has
// a handful of faces: comparing each with those before it beats sorting.
int corner_excess(const std::vector<int>& ids) {
  int distinct = 0;
  for (size_t i = 0; i < ids.size(); ++i)
    if (std::find(ids.begin(), ids.begin() + i, ids[i]) == ids.begin() + i) ++distinct;
  return std::max(0, distinct - 3);
}

// The same conditions as validate_labels, without listing faces.
int violation_score(const MeshAdjacency& adjacency, const Charts& ch) {
  std::vector<std::uint64_t> pairs;
  for (int e = 0; e < adjacency.edge_count(); ++e)
    for (int i = adjacency.edge_offsets[e]; i < adjacency.edge_offsets[e + 1]; ++i)
      for (int j = i + 1; j < adjacency.edge_offsets[e + 1]; ++j) {
        const std::uint64_t a = ch.of_face[adjacency.edge_faces[i]], b = ch.of_face[adjacency.edge_faces[j]];
        if (a != b) pairs.push_back(std::min(a, b) << 32 | std::max(a, b));
      }
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  std::vector<int> neighbours(ch.count(), 0);
  int score = 0;
  for (std::uint64_t p : pairs) {
    const int a = static_cast<int>(p >> 32), b = static_cast<int>(p & 0xffffffffu);
    ++neighbours[a];
    ++neighbours[b];
    if ((ch.label[a] ^ 1) == ch.label[b]) score += 2;
  }
  const std::vector<char> open_side = charts_with_open_side(adjacency, ch);
  for (int c = 0; c < ch.count(); ++c)
    if (!open_side[c]) score += std::max(0, 4 - neighbours[c]);
  std::vector<int> around;
  const int vertex_count = static_cast<int>(adjacency.vertex_offsets.size()) - 1;
  for (int v = 0; v < vertex_count; ++v) {
    around.clear();
    for (int k = adjacency.vertex_offsets[v]; k < adjacency.vertex_offsets[v + 1]; ++k) {
      const int c = ch.of_face[adjacency.vertex_faces[k]];
      if (std::find(around.begin(), around.end(), c) == around.end()) around.push_back(c);
    }
    score += std::max(0, static_cast<int>(around.size()) - 3);
  }
  return score;
}

}  // namespace

int violation_score(const MeshAdjacency& adjacency, const std::vector<int>& labels) {
  return violation_score(adjacency, charts(adjacency, labels));
}

std::vector<std::vector<int>> face_edges(const MeshAdjacency& adjacency, int face_count) {
  std::vector<std::vector<int>> result(face_count);
  for (int e = 0; e < adjacency.edge_count(); ++e)
    for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k) {
      std::vector<int>& edges = result[adjacency.edge_faces[k]];
      if (edges.empty() || edges.back() != e) edges.push_back(e);
    }
  return result;
}

ViolationDelta::ViolationDelta(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& edges_of_face,
                               const std::vector<int>& labels)
    : adjacency_(adjacency), edges_of_face_(edges_of_face), charts_(polycube::charts(adjacency, labels)) {
  faces_of_chart_ = chart_faces(charts_);
  neighbours_.resize(charts_.count());
  for (const ChartBoundary& b : chart_boundaries(adjacency, charts_)) {
    neighbours_[b.charts[0]].push_back(b.charts[1]);
    neighbours_[b.charts[1]].push_back(b.charts[0]);
  }
  for (std::vector<int>& n : neighbours_) std::sort(n.begin(), n.end());
  open_side_ = charts_with_open_side(adjacency, charts_);
  score_ = violation_score(adjacency, charts_);
  chart_stamp_.assign(charts_.count(), 0);
  face_stamp_.assign(labels.size(), 0);
  local_of_face_.assign(labels.size(), -1);
  edge_stamp_.assign(adjacency.edge_count(), 0);
  vertex_stamp_.assign(adjacency.vertex_offsets.size() - 1, 0);
  excess_at_vertex_.resize(vertex_stamp_.size());
  for (size_t v = 0; v < excess_at_vertex_.size(); ++v) excess_at_vertex_[v] = own_excess_at(static_cast<int>(v));
}

int ViolationDelta::own_excess_at(int v) {
  std::vector<int>& ids = scratch_.ids;
  ids.clear();
  for (int k = adjacency_.vertex_offsets[v]; k < adjacency_.vertex_offsets[v + 1]; ++k)
    ids.push_back(charts_.of_face[adjacency_.vertex_faces[k]]);
  return corner_excess(ids);
}

int ViolationDelta::score_of(const std::vector<int>& candidate, const std::vector<int>& changed) {
  const int s = ++stamp_;
  const std::vector<int>& offsets = adjacency_.edge_offsets;
  const std::vector<int>& on_edge = adjacency_.edge_faces;

  // The region: every face of the charts that hold or touch a changed face.
  std::vector<int>& region_charts = scratch_.region_charts;
  std::vector<int>& region = scratch_.region;
  region_charts.clear();
  region.clear();
  auto add_chart = [&](int c) {
    if (chart_stamp_[c] == s) return;
    chart_stamp_[c] = s;
    region_charts.push_back(c);
  };
  for (int f : changed) {
    add_chart(charts_.of_face[f]);
    for (int e : edges_of_face_[f])
      for (int k = offsets[e]; k < offsets[e + 1]; ++k) add_chart(charts_.of_face[on_edge[k]]);
  }
  for (int c : region_charts)
    for (int f : faces_of_chart_[c]) {
      face_stamp_[f] = s;
      local_of_face_[f] = static_cast<int>(region.size());
      region.push_back(f);
    }
  std::vector<int>& edges = scratch_.edges;
  std::vector<int>& vertices = scratch_.vertices;
  edges.clear();
  vertices.clear();
  for (int f : region)
    for (int e : edges_of_face_[f]) {
      if (edge_stamp_[e] == s) continue;
      edge_stamp_[e] = s;
      edges.push_back(e);
      for (int v : adjacency_.edges[e])
        if (vertex_stamp_[v] != s) vertex_stamp_[v] = s, vertices.push_back(v);
    }

  // The region's charts after the change: outside it no chart changes.
  UnionFind& sets = scratch_.sets;
  sets.reset(static_cast<int>(region.size()));
  for (int e : edges)
    for (int i = offsets[e]; i < offsets[e + 1]; ++i)
      for (int j = i + 1; j < offsets[e + 1]; ++j) {
        const int a = on_edge[i], b = on_edge[j];
        if (face_stamp_[a] == s && face_stamp_[b] == s && candidate[a] == candidate[b])
          sets.join(local_of_face_[a], local_of_face_[b]);
      }
  const int base = charts_.count();  // new charts are numbered from here
  std::vector<int>& new_label = scratch_.new_label;
  std::vector<int>& id_of_root = scratch_.id_of_root;
  std::vector<int>& new_id = scratch_.new_id;
  new_label.clear();
  id_of_root.assign(region.size(), -1);
  new_id.resize(region.size());
  for (size_t i = 0; i < region.size(); ++i) {
    const int r = sets.root(static_cast<int>(i));
    if (id_of_root[r] < 0) {
      id_of_root[r] = static_cast<int>(new_label.size());
      new_label.push_back(candidate[region[r]]);
    }
    new_id[i] = base + id_of_root[r];
  }
  auto after = [&](int f) { return face_stamp_[f] == s ? new_id[local_of_face_[f]] : charts_.of_face[f]; };
  auto label_after = [&](int id) { return id >= base ? new_label[id - base] : charts_.label[id]; };

  // Boundaries touching the region, before and after.
  std::vector<std::uint64_t>& before_pairs = scratch_.before_pairs;
  std::vector<std::uint64_t>& after_pairs = scratch_.after_pairs;
  std::vector<char>& new_open = scratch_.new_open;
  before_pairs.clear();
  after_pairs.clear();
  new_open.assign(new_label.size(), 0);
  for (int e : edges) {
    if (offsets[e + 1] - offsets[e] == 1 && face_stamp_[on_edge[offsets[e]]] == s)
      new_open[after(on_edge[offsets[e]]) - base] = 1;
    for (int i = offsets[e]; i < offsets[e + 1]; ++i)
      for (int j = i + 1; j < offsets[e + 1]; ++j) {
        const int a = on_edge[i], b = on_edge[j];
        if (charts_.of_face[a] != charts_.of_face[b])
          before_pairs.push_back(pair_key(charts_.of_face[a], charts_.of_face[b]));
        if (after(a) != after(b)) after_pairs.push_back(pair_key(after(a), after(b)));
      }
  }
  for (std::vector<std::uint64_t>* pairs : {&before_pairs, &after_pairs}) {
    std::sort(pairs->begin(), pairs->end());
    pairs->erase(std::unique(pairs->begin(), pairs->end()), pairs->end());
  }

  int before = 0, now = 0;
  // Opposite charts side by side.
  for (std::uint64_t p : before_pairs)
    if ((charts_.label[p >> 32] ^ 1) == charts_.label[p & 0xffffffffu]) before += 2;
  std::vector<int>& new_neighbours = scratch_.new_neighbours;
  new_neighbours.assign(new_label.size(), 0);
  std::vector<int>& outside = scratch_.outside;  // unchanged charts beside the region, once per new chart beside them
  outside.clear();
  for (std::uint64_t p : after_pairs) {
    const int a = static_cast<int>(p >> 32), b = static_cast<int>(p & 0xffffffffu);
    if ((label_after(a) ^ 1) == label_after(b)) now += 2;
    for (int c : {a, b})
      if (c >= base) ++new_neighbours[c - base];
    if (a < base && b >= base) outside.push_back(a);  // a < b: an unchanged chart has the smaller id
  }
  // Missing neighbours: the region's charts, and the unchanged charts beside
  // them (whose neighbours in the region changed).
  for (int c : region_charts)
    if (!open_side_[c]) before += missing_neighbours(neighbours_[c].size());
  for (size_t k = 0; k < new_label.size(); ++k)
    if (!new_open[k]) now += missing_neighbours(new_neighbours[k]);
  std::sort(outside.begin(), outside.end());
  for (size_t i = 0; i < outside.size();) {
    size_t j = i;
    while (j < outside.size() && outside[j] == outside[i]) ++j;
    const int c = outside[i];
    if (!open_side_[c]) {
      int kept = 0;
      for (int n : neighbours_[c]) kept += chart_stamp_[n] != s;
      before += missing_neighbours(neighbours_[c].size());
      now += missing_neighbours(kept + (j - i));
    }
    i = j;
  }
  // Corners: the vertices of the region's faces.
  std::vector<int>& ids = scratch_.ids;
  for (int v : vertices) {
    before += excess_at_vertex_[v];
    ids.clear();
    for (int k = adjacency_.vertex_offsets[v]; k < adjacency_.vertex_offsets[v + 1]; ++k)
      ids.push_back(after(adjacency_.vertex_faces[k]));
    now += corner_excess(ids);
  }
  last_score_ = score_ - before + now;
  return last_score_;
}

void ViolationDelta::keep_last() {
  const int s = stamp_;
  const std::vector<int>& region = scratch_.region;
  const std::vector<int>& new_label = scratch_.new_label;
  const int base = charts_.count();
  for (int c : scratch_.region_charts) {
    faces_of_chart_[c].clear();
    neighbours_[c].clear();
    charts_.faces[c] = 0;
  }
  const int added = static_cast<int>(new_label.size());
  charts_.label.insert(charts_.label.end(), new_label.begin(), new_label.end());
  charts_.faces.resize(base + added, 0);
  faces_of_chart_.resize(base + added);
  neighbours_.resize(base + added);
  open_side_.insert(open_side_.end(), scratch_.new_open.begin(), scratch_.new_open.end());
  chart_stamp_.resize(base + added, 0);
  for (size_t i = 0; i < region.size(); ++i) {
    const int c = scratch_.new_id[i];
    charts_.of_face[region[i]] = c;
    faces_of_chart_[c].push_back(region[i]);
    ++charts_.faces[c];
  }
  for (int c = base; c < base + added; ++c) std::sort(faces_of_chart_[c].begin(), faces_of_chart_[c].end());
  // Unchanged charts beside the region lose the region's old charts as
  // neighbours and gain its new ones.
  // (Each chart beside an old one is beside a new one: the faces on their
  // shared edges are all in the region.)
  // score_of() left `outside` sorted, a chart once per new chart beside it: each once here.
  std::vector<int>& beside = scratch_.outside;
  beside.erase(std::unique(beside.begin(), beside.end()), beside.end());
  for (int c : beside) {
    std::vector<int>& n = neighbours_[c];
    n.erase(std::remove_if(n.begin(), n.end(), [&](int d) { return d < base && chart_stamp_[d] == s; }), n.end());
  }
  for (std::uint64_t p : scratch_.after_pairs) {
    const int a = static_cast<int>(p >> 32), b = static_cast<int>(p & 0xffffffffu);
    if (a < base && b < base) continue;  // two unchanged charts: kept as they were
    neighbours_[a].push_back(b);
    neighbours_[b].push_back(a);
  }
  for (int c : beside) std::sort(neighbours_[c].begin(), neighbours_[c].end());
  for (int c = base; c < base + added; ++c) std::sort(neighbours_[c].begin(), neighbours_[c].end());
  for (int v : scratch_.vertices) excess_at_vertex_[v] = own_excess_at(v);
  score_ = last_score_;
}

}  // namespace polycube
