// The report of a deformation run as JSON: the one place its keys are named,
// so the command-line report, the Python module's dict and the Blender panel
// agree (docs/design.md section 4 for the figures).
#pragma once

#include <string>

#include "deform/deform.h"
#include "io/json.h"

namespace polycube {

// Adds the figures of section 4 as members of the object json.
void add_figures(Json& json, const Figures& figures);

// vertices, faces, triangles, iterations, converged, stopped, unlabelled_faces,
// variant, tolerance_deg, the figures, and seconds per phase. A caller can add
// what only it knows (the program's memory).
Json deform_report(const PolygonMesh& mesh, const DeformResult& result, const DeformOptions& options);

}  // namespace polycube
