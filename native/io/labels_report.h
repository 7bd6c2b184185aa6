// Label validation and orientation as JSON: the one place their keys are
// named, so `polycube validate --json` and the Python module's dicts agree.
#pragma once

#include <string>

#include "labels/orientation.h"
#include "labels/validate_labels.h"
#include "io/json.h"

namespace polycube {

// valid, charts, boundaries, corners, unlabelled_faces, and violations: a list
// of {kind, chart, label, others, vertex, faces}, as members of the object json.
void add_validation(Json& json, const LabelValidation& validation);

// orientable, consistent, inconsistent_edges, components, closed_components,
// inward_components, inward, and with labels area_against_labels and labels_opposite.
void add_orientation(Json& json, const Orientation& orientation, bool with_labels);

}  // namespace polycube
