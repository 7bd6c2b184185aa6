#include "core/repair_labels.h"

#include <algorithm>
#include <cstdint>

#include "core/charts.h"
#include "core/validate_labels.h"

namespace polycube {

int violation_score(const MeshAdjacency& adjacency, const std::vector<int>& labels) {
  // The same conditions as validate_labels, without listing faces: this runs
  // once per candidate move.
  const Charts ch = charts(adjacency, labels);
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
  for (int n : neighbours) score += std::max(0, 4 - n);
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

namespace {

struct Move {
  std::vector<int> faces;
  int label;
};

// The faces of `chart` within `depth` edge-steps of `seed` faces (seed faces
// of other charts are skipped).
std::vector<int> band(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& face_edges,
                      const Charts& ch, int chart, const std::vector<int>& seed, int depth) {
  std::vector<int> result;
  for (int f : seed)
    if (ch.of_face[f] == chart) result.push_back(f);
  std::vector<int> frontier = result;
  for (int step = 1; step < depth; ++step) {
    std::vector<int> next;
    for (int f : frontier)
      for (int e : face_edges[f])
        for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k) {
          const int g = adjacency.edge_faces[k];
          if (ch.of_face[g] == chart && std::find(result.begin(), result.end(), g) == result.end()) {
            result.push_back(g);
            next.push_back(g);
          }
        }
    frontier = std::move(next);
  }
  std::sort(result.begin(), result.end());
  return result;
}

std::vector<Move> candidate_moves(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& face_edges,
                                  const Charts& ch, const std::vector<std::vector<int>>& chart_faces,
                                  const LabelViolation& v) {
  std::vector<Move> moves;
  switch (v.kind) {
    case ViolationKind::kTooFewNeighbours:
      for (int l = 0; l < 6; ++l)
        if (l != v.label) moves.push_back({v.faces, l});
      break;
    case ViolationKind::kOppositeNeighbours: {
      const int other = v.others[0];
      for (int l = 0; l < 6; ++l) {
        if (l / 2 == v.label / 2) continue;  // the orthogonal labels only
        moves.push_back({chart_faces[v.chart], l});
        for (int chart : {v.chart, other})
          for (int depth : {1, 2}) moves.push_back({band(adjacency, face_edges, ch, chart, v.faces, depth), l});
      }
      break;
    }
    case ViolationKind::kCornerTooManyCharts: {
      std::vector<int> at_corner = v.others;
      at_corner.push_back(v.chart);
      for (int chart : at_corner) {
        std::vector<int> faces;
        for (int f : v.faces)
          if (ch.of_face[f] == chart) faces.push_back(f);
        for (int target : at_corner)
          if (ch.label[target] != ch.label[chart]) moves.push_back({faces, ch.label[target]});
      }
      break;
    }
  }
  return moves;
}

}  // namespace

std::vector<int> repair_labels(const MeshAdjacency& adjacency, const LabelEnergy& energy, std::vector<int> labels,
                               int rounds) {
  const int vertex_count = static_cast<int>(adjacency.vertex_offsets.size()) - 1;
  const int face_count = static_cast<int>(labels.size());
  std::vector<std::vector<int>> face_edges(face_count);
  for (int e = 0; e < adjacency.edge_count(); ++e)
    for (int k = adjacency.edge_offsets[e]; k < adjacency.edge_offsets[e + 1]; ++k)
      face_edges[adjacency.edge_faces[k]].push_back(e);

  int score = violation_score(adjacency, labels);
  for (int round = 0; round < rounds && score > 0; ++round) {
    const Charts ch = charts(adjacency, labels);
    const LabelValidation validation = validate_labels(adjacency, ch, vertex_count);
    std::vector<std::vector<int>> chart_faces(ch.count());
    for (int f = 0; f < face_count; ++f) chart_faces[ch.of_face[f]].push_back(f);
    bool moved = false;
    for (const LabelViolation& v : validation.violations) {
      int best_score = score;
      double best_energy = 0.0;
      std::vector<int> best;
      for (const Move& move : candidate_moves(adjacency, face_edges, ch, chart_faces, v)) {
        if (move.faces.empty()) continue;
        std::vector<int> candidate = labels;
        for (int f : move.faces) candidate[f] = move.label;
        const int s = violation_score(adjacency, candidate);
        if (s >= score || s > best_score) continue;  // only moves that fix something, the best of them
        const double e = energy(candidate);
        if (best.empty() || s < best_score || e < best_energy) {
          best_score = s;
          best_energy = e;
          best = std::move(candidate);
        }
      }
      if (!best.empty()) {
        labels = std::move(best);
        score = best_score;
        moved = true;
        break;
      }
    }
    if (!moved) break;
  }
  return labels;
}

}  // namespace polycube
