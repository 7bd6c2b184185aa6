#include "io/labels_report.h"

#include "labels/axis.h"

namespace polycube {

void add_validation(JsonWriter& json, const LabelValidation& v) {
  json.add("valid", v.valid())
      .add("realisable", v.realisable())
      .add("charts", v.charts)
      .add("boundaries", v.boundaries)
      .add("corners", v.corners)
      .add("unlabelled_faces", v.unlabelled_faces)
      .begin_array("violations");
  for (const LabelViolation& violation : v.violations)
    json.begin_object()
        .add("kind", violation_kind_name(violation.kind))
        .add("chart", violation.chart)
        .add("label", violation.label)
        .add("label_name", kLabelNames[violation.label])
        .add("others", violation.others)
        .add("vertex", violation.vertex)
        .add("faces", violation.faces)
        .end();
  json.end();
}

void add_orientation(JsonWriter& json, const Orientation& o, bool with_labels) {
  json.add("orientable", o.orientable)
      .add("consistent", o.consistent)
      .add("inconsistent_edges", o.inconsistent_edges)
      .add("components", o.components)
      .add("closed_components", o.closed_components)
      .add("inward_components", o.inward_components)
      .add("inward", o.inward());
  if (with_labels) json.add("area_against_labels", o.area_against_labels).add("labels_opposite", o.labels_opposite);
}

}  // namespace polycube
