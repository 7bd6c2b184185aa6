// How far a labeling is from the polycube conditions (docs/design.md
// section 3.2), as one number the repair (repair_charts.h) lowers: each
// missing neighbour of a chart that does not reach the mesh border, each pair
// of opposite charts side by side (twice) and each chart beyond three at a
// vertex. 0 for a valid labeling.
//
// The repair scores thousands of candidate moves per labeling, each changing
// a few faces. Recounting the whole mesh per candidate was most of the
// labeller's time (armadillo: 60%); ViolationDelta recounts only the charts
// the changed faces are in or touch, and gives the same number.
#pragma once

#include <cstdint>
#include <vector>

#include "labels/charts.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/union_find.h"

namespace polycube {

// labels: 0..5, one per face.
int violation_score(const MeshAdjacency& adjacency, const std::vector<int>& labels);

// The edges of each face (the faces_of_edge lists turned around), built once per mesh.
std::vector<std::vector<int>> face_edges(const MeshAdjacency& adjacency, int face_count);

// The score of labelings that differ from `labels` only on some faces.
// Why it is exact: a chart neither holding a changed face nor sharing an
// edge with one keeps its faces and its label, so only the others (the
// region) are rebuilt, and only the boundaries, neighbour counts and vertices
// that touch the region can change.
class ViolationDelta {
 public:
  ViolationDelta(const MeshAdjacency& adjacency, const std::vector<std::vector<int>>& edges_of_face,
                 const std::vector<int>& labels);

  int score() const { return score_; }
  // Of the labels given above.
  const Charts& charts() const { return charts_; }
  const std::vector<std::vector<int>>& faces_of_chart() const { return faces_of_chart_; }
  const std::vector<std::vector<int>>& neighbours() const { return neighbours_; }  // per chart, ascending

  // `candidate` equals the labels given above outside `changed` (faces that
  // may differ; listing unchanged ones too is fine).
  int score_of(const std::vector<int>& candidate, const std::vector<int>& changed);
  // Makes the candidate of the last score_of() call this object's labels
  // (and its score this one's), rebuilding only that call's region: a
  // caller that keeps moves one by one (keep_valid_moves.h) then scores each
  // against a region around that move alone, never a whole recount. The
  // region's old charts stay as empty entries of charts(), and new ones are
  // numbered after them.
  void keep_last();

 private:
  // Charts beyond three at vertex v, of this object's own labels.
  int own_excess_at(int v);

  const MeshAdjacency& adjacency_;
  const std::vector<std::vector<int>>& edges_of_face_;
  Charts charts_;
  std::vector<std::vector<int>> faces_of_chart_;
  std::vector<std::vector<int>> neighbours_;  // per chart, ascending
  std::vector<char> open_side_;
  std::vector<int> excess_at_vertex_;  // charts beyond three, per vertex, of the labels above
  int score_ = 0;
  int last_score_ = 0;  // of the last score_of() call
  // Scratch, reused between calls: stamps mark membership for one call.
  int stamp_ = 0;
  std::vector<int> chart_stamp_, face_stamp_, edge_stamp_, vertex_stamp_, local_of_face_;
  // The lists one call builds, kept with their capacity: the repair makes
  // thousands of calls, and allocating them anew was a tenth of the
  // labeller's time (bunny00).
  struct Scratch {
    std::vector<int> region_charts, region, edges, vertices, new_label, id_of_root, new_id, new_neighbours, outside,
        ids;
    std::vector<std::uint64_t> before_pairs, after_pairs;
    std::vector<char> new_open;
    UnionFind sets;
  } scratch_;
};

}  // namespace polycube
