// Where a command's labels come from: a labels file, `nearest` (the axis
// nearest each normal) or `auto` (the automatic labeller), optionally flipped
// for the other winding; and a warning on stderr when the labels mostly face
// away from the normals or the mesh is wound inward or cannot be oriented.
#pragma once

#include <string>
#include <vector>

#include "mesh/mesh.h"

namespace polycube {

struct AutoLabelOptions;
class Arguments;

// The labeller's options from --detail D (0..1) and --compactness W (which
// overrides the compactness --detail sets).
AutoLabelOptions auto_label_options(const Arguments& arguments);

std::vector<int> labels_from_source(const std::string& source, const PolygonMesh& mesh,
                                    const AutoLabelOptions& options, bool flip);

// Prints one line per orientation problem to stderr; returns whether any.
bool warn_about_orientation(const PolygonMesh& mesh, const std::vector<int>& labels, bool flipped);

}  // namespace polycube
