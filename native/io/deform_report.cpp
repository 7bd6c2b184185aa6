#include "io/deform_report.h"

#include <algorithm>

namespace polycube {
namespace {

// Face lists can be as long as the mesh on a hopeless labeling; the counts are
// exact, the lists keep the first kMaxListedFaces ids (ascending).
constexpr size_t kMaxListedFaces = 1000;

void add_faces(JsonWriter& json, const std::string& key, const std::vector<int>& faces) {
  json.add(key + "_count", static_cast<long>(faces.size()));
  json.add(key, std::vector<int>(faces.begin(), faces.begin() + std::min(faces.size(), kMaxListedFaces)));
}

}  // namespace

void add_figures(JsonWriter& json, const Figures& f) {
  json.add("normal_deviation_max_deg", f.normal_deviation_max_deg)
      .add("normal_deviation_mean_deg", f.normal_deviation_mean_deg)
      .add("edge_error", f.edge_error)
      .add("area_error", f.area_error)
      .add("flipped_faces", f.flipped_faces)
      .add("collapsed_faces", f.collapsed_faces)
      .add("collapsed_area", f.collapsed_area)
      .add("folded_edges", f.folded_edges)
      .add("nearest_axis_deviation_max_deg", f.nearest_axis_deviation_max_deg);
}

JsonWriter deform_report(const PolygonMesh& mesh, const DeformResult& r, const DeformOptions& options) {
  JsonWriter json;
  json.add("vertices", static_cast<long>(mesh.vertices.rows()))
      .add("faces", mesh.faces.count())
      .add("triangles", r.triangles)
      .add("variant", variant_name(options.variant))
      .add("tolerance_deg", options.tolerance_deg)
      .add("iterations", r.iterations)
      .add("kept_iteration", r.kept_iteration)
      .add("input_folded_edges", r.input_folded_edges)
      .add("converged", r.converged)
      .add("stopped", r.stopped)
      .add("failure", r.failure)
      .add("flat_iteration", r.flat_iteration)
      .add("collapsed_on_purpose", r.collapsed_on_purpose)
      .add("unlabelled_faces", r.unlabelled_faces)
      .add("solver", r.solver)
      .add("factorizations", r.factorizations);
  add_figures(json, r.figures);
  add_faces(json, "unconverged_faces", r.unconverged_faces);
  add_faces(json, "flipped_face_ids", r.flipped_faces);
  add_faces(json, "relabelled_faces", r.relabelled_faces);
  json.begin_object("given_labels");
  add_figures(json, r.given_labels_figures);
  json.end();
  json.begin_array("flatten_attempts");
  for (const auto& a : r.flatten_attempts)
    json.begin_object()
        .add("iteration", a.iteration)
        .add("rounds", a.rounds)
        .add("folds_left", a.folds_left)
        .add("collapsed_area", a.collapsed_area)
        .add("kept", a.kept)
        .end();
  json.end();
  json.begin_object("seconds")
      .add("total", r.seconds.total)
      .add("assemble", r.seconds.assemble)
      .add("factorize", r.seconds.factorize)
      .add("rotations", r.seconds.rotations)
      .add("solve", r.seconds.solve)
      .add("measure", r.seconds.measure)
      .end();
  return json;
}

}  // namespace polycube
