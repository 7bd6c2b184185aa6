#include "io/deform_report.h"

#include <algorithm>

namespace polycube {
namespace {

// Face lists can be as long as the mesh on a hopeless labeling; the counts are
// exact, the lists keep the first kMaxListedFaces ids (ascending).
constexpr size_t kMaxListedFaces = 1000;

void add_faces(Json& json, const std::string& key, const std::vector<int>& faces) {
  json[key + "_count"] = faces.size();
  json[key] = std::vector<int>(faces.begin(), faces.begin() + std::min(faces.size(), kMaxListedFaces));
}

}  // namespace

void add_figures(Json& json, const Figures& f) {
  json["normal_deviation_max_deg"] = f.normal_deviation_max_deg;
  json["normal_deviation_mean_deg"] = f.normal_deviation_mean_deg;
  json["edge_error"] = f.edge_error;
  json["area_error"] = f.area_error;
  json["max_area_ratio"] = f.max_area_ratio;
  json["flipped_faces"] = f.flipped_faces;
  json["collapsed_faces"] = f.collapsed_faces;
  json["collapsed_area"] = f.collapsed_area;
  json["folded_edges"] = f.folded_edges;
  json["nearest_axis_deviation_max_deg"] = f.nearest_axis_deviation_max_deg;
}

Json deform_report(const PolygonMesh& mesh, const DeformResult& r, const DeformOptions& options) {
  Json json = {{"vertices", mesh.vertices.rows()},
               {"faces", mesh.faces.count()},
               {"triangles", r.triangles},
               {"variant", variant_name(options.variant)},
               {"tolerance_deg", options.tolerance_deg},
               {"iterations", r.iterations},
               {"kept_iteration", r.kept_iteration},
               {"input_folded_edges", r.input_folded_edges},
               {"converged", r.converged},
               {"stopped", r.stopped},
               {"failure", r.failure},
               {"flat_iteration", r.flat_iteration},
               {"second_run_iterations", r.second_run_iterations},
               {"last_resort", r.last_resort},
               {"polish_steps", r.polish_steps},
               {"coarse_triangles", r.coarse_triangles},
               {"coarse_iterations", r.coarse_iterations},
               {"collapsed_on_purpose", r.collapsed_on_purpose},
               {"unlabelled_faces", r.unlabelled_faces},
               {"solver", r.solver},
               {"factorizations", r.factorizations},
               {"back_substitutions", r.back_substitutions}};
  add_figures(json, r.figures);
  add_faces(json, "unconverged_faces", r.unconverged_faces);
  add_faces(json, "flipped_face_ids", r.flipped_faces);
  add_faces(json, "relabelled_faces", r.relabelled_faces);
  add_figures(json["given_labels"] = Json::object(), r.given_labels_figures);
  Json& attempts = json["flatten_attempts"] = Json::array();
  for (const auto& a : r.flatten_attempts)
    attempts.push_back({{"iteration", a.iteration},
                        {"rounds", a.rounds},
                        {"folds_left", a.folds_left},
                        {"collapsed_area", a.collapsed_area},
                        {"kept", a.kept},
                        {"factorizations", a.factorizations},
                        {"untangle_rounds", a.untangle_rounds},
                        {"seconds", a.seconds},
                        {"untangle_seconds", a.untangle_seconds}});
  json["seconds"] = {{"total", r.seconds.total},         {"assemble", r.seconds.assemble},
                     {"factorize", r.seconds.factorize}, {"rotations", r.seconds.rotations},
                     {"solve", r.seconds.solve},         {"measure", r.seconds.measure}};
  Json& stages = json["stages"] = Json::object();
  const std::pair<const char*, const StageCost*> stage_costs[] = {
      {"set_up", &r.stages.set_up},   {"fit", &r.stages.fit},         {"continuous", &r.stages.continuous},
      {"relax", &r.stages.relax},     {"flatten", &r.stages.flatten}, {"untangle", &r.stages.untangle},
      {"measure", &r.stages.measure}, {"polish", &r.stages.polish}};
  for (const auto& [name, cost] : stage_costs) stages[name] = {{"count", cost->count}, {"seconds", cost->seconds}};
  stages["current_steps"] = r.stages.current_steps;
  if (options.time_references)
    json["reference_seconds"] = {{"factorize", r.reference_factorize_seconds},
                                 {"solve", r.reference_solve_seconds},
                                 {"measure", r.reference_measure_seconds}};
  return json;
}

}  // namespace polycube
