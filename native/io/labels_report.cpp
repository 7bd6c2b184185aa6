#include "io/labels_report.h"

#include "labels/axis.h"

namespace polycube {

void add_validation(Json& json, const LabelValidation& v) {
  json["valid"] = v.valid();
  json["realisable"] = v.realisable();
  json["charts"] = v.charts;
  json["boundaries"] = v.boundaries;
  json["corners"] = v.corners;
  json["unlabelled_faces"] = v.unlabelled_faces;
  Json& violations = json["violations"] = Json::array();
  for (const LabelViolation& violation : v.violations)
    violations.push_back({{"kind", violation_kind_name(violation.kind)},
                          {"chart", violation.chart},
                          {"label", violation.label},
                          {"label_name", kLabelNames[violation.label]},
                          {"others", violation.others},
                          {"vertex", violation.vertex},
                          {"faces", violation.faces}});
}

void add_orientation(Json& json, const Orientation& o, bool with_labels) {
  json["orientable"] = o.orientable;
  json["consistent"] = o.consistent;
  json["inconsistent_edges"] = o.inconsistent_edges;
  json["components"] = o.components;
  json["closed_components"] = o.closed_components;
  json["inward_components"] = o.inward_components;
  json["inward"] = o.inward();
  if (with_labels) {
    json["area_against_labels"] = o.area_against_labels;
    json["labels_opposite"] = o.labels_opposite;
  }
}

}  // namespace polycube
