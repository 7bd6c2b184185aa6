// The coarse route (deform/coarse_to_fine.h), on fandisk with a coarse mesh
// of 3,000 triangles: the route applies from 12,000 triangles, and fandisk
// has 12,946.
#include <gtest/gtest.h>

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "deform/coarse_to_fine.h"
#include "deform/finished_run.h"
#include "io/read_mesh.h"
#include "labels/nearest_labels.h"
#include "labels/violation_score.h"
#include "mesh/mesh_adjacency.h"
#include "mesh/unit_box.h"

namespace polycube {
namespace {

// Labels that break the polycube conditions go to the route at once: the
// result is the route's from a hand-over with no run before it, iteration
// for iteration. Stage 8 and the polish are off, so the route's result is
// deform's. (At this size the mesh's own run would flatten fandisk's
// nearest labels by its rounds, and no route would be taken; at the
// default's scale, 200,000 triangles and more, no labels breaking the
// conditions did: docs/design.md section 2.8.)
TEST(CoarseToFine, LabelsThatBreakTheConditionsGoToTheRouteAtOnce) {
  const std::string path = std::string(POLYCUBE_MESH_DATA) + "/fandisk.off";
  if (!std::ifstream(path).good()) GTEST_SKIP() << "fandisk.off is missing: run `make data`";
  const PolygonMesh input = read_mesh(path);
  const UnitBoxMesh unit(input);
  const PolygonMesh& mesh = unit.mesh();
  const std::vector<int> labels = nearest_labels(mesh);
  ASSERT_GT(violation_score(mesh_adjacency(mesh.faces, static_cast<int>(mesh.vertices.rows())), labels), 0);
  DeformOptions options;
  options.iterations = 50;
  options.coarse_triangles = 3000;
  options.relabel_collapsed = false;
  options.polish = false;
  const DeformResult whole = deform(mesh, labels, options);

  DeformResult handed_over, routed;
  handed_over.handed_over = true;
  std::unique_ptr<FinishedRun> finished;
  ASSERT_TRUE(coarse_to_fine(mesh, labels, options, {}, handed_over, routed, finished));
  ASSERT_GT(whole.coarse_triangles, 0);
  EXPECT_EQ(whole.coarse_triangles, routed.coarse_triangles);
  EXPECT_EQ(whole.coarse_iterations, routed.coarse_iterations);
  EXPECT_EQ(whole.iterations, routed.iterations);
  EXPECT_TRUE(whole.converged);
  EXPECT_EQ(whole.figures.flipped_faces, 0);
  EXPECT_LE(whole.figures.folded_edges, whole.input_folded_edges);
}

}  // namespace
}  // namespace polycube
