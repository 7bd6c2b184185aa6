// deform(): the set-up (deformation.h), then the paper's iteration
// (paper_iteration.h) or the robust variant's stages (robust_run.h), then
// the result.
#include "deform/deform.h"

#include "deform/deformation.h"
#include "deform/finished_run.h"
#include "deform/paper_iteration.h"
#include "deform/robust_run.h"
#include "mesh/check_input.h"

namespace polycube {

Variant parse_variant(const std::string& name) {
  for (Variant variant : kVariants)
    if (name == variant_name(variant)) return variant;
  throw Error("unknown variant '" + name + "': use 'robust', 'fixed' or 'current'");
}

const char* variant_name(Variant variant) {
  switch (variant) {
    case Variant::kFixed:
      return "fixed";
    case Variant::kCurrent:
      return "current";
    case Variant::kRobust:
      break;
  }
  return "robust";
}

namespace {

void check_run(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options) {
  check_input(mesh, &labels);
  if (options.iterations < 0) throw Error("the iteration limit must be 0 or more");
  if (!(options.tolerance_deg >= 0.0)) throw Error("the tolerance must be 0 or more degrees");
  if (options.start.size() > 0 && (options.start.rows() != mesh.vertices.rows() || !options.start.allFinite()))
    throw Error("the start positions must be finite, one row per vertex of the mesh");
}

// The iterations of the variant on `deformation`, just built, and the
// result; a robust run's last flat charts go to `planes`.
DeformResult iterate(Deformation& deformation, std::unique_ptr<ChartPlanes>& planes) {
  // A solve that breaks down after some iterations (the paper's `current`
  // variant on armadillo: its triangles degenerate until the Laplacian is
  // singular) ends the run with what was done, not with nothing.
  try {
    if (deformation.options.variant == Variant::kRobust)
      planes = robust_iteration(deformation);
    else
      paper_iteration(deformation);
  } catch (const Error& e) {
    if (deformation.result.iterations == 0) throw;
    deformation.result.failure = e.what();
  }
  return deformation.conclude();
}

}  // namespace

DeformResult deform_in_unit_box(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                                const IterationCallback& callback) {
  check_run(mesh, labels, options);
  Deformation deformation(mesh, labels, options, callback);
  std::unique_ptr<ChartPlanes> planes;
  return iterate(deformation, planes);
}

DeformResult deform_in_unit_box(const PolygonMesh& mesh, const std::vector<int>& labels, const DeformOptions& options,
                                const IterationCallback& callback, std::unique_ptr<FinishedRun>& finished,
                                const Vertices& near, NearStart near_start, bool hand_over_unflat) {
  check_run(mesh, labels, options);
  auto run = std::make_unique<FinishedRun>();
  run->options = options;
  run->labels = labels;
  run->callback = callback;
  run->deformation = std::make_unique<Deformation>(mesh, run->labels, run->options, run->callback, near);
  run->deformation->near_start = near_start;
  run->deformation->hand_over_unflat = hand_over_unflat;
  DeformResult result = iterate(*run->deformation, run->planes);
  run->callback = nullptr;
  finished = std::move(run);
  return result;
}

}  // namespace polycube
