// Where a command's labels come from: a labels file, `nearest` (the axis
// nearest each normal) or `auto` (the automatic labeller), optionally flipped
// for the other winding; and a warning on stderr when the labels mostly face
// away from the normals or the mesh is wound inward or cannot be oriented.
#pragma once

#include <string>
#include <vector>

#include "cli/arguments.h"
#include "io/labels_io.h"
#include "mesh/mesh.h"

namespace polycube {

struct AutoLabelOptions;

// What the command line says about labels.
struct LabelSource {
  std::string labels = "nearest";  // nearest, auto or a labels file
  bool flip = false;               // --flip-labels
  double detail = 0.5;             // --detail D, 0..1
  double compactness = -1.0;       // --compactness W; negative: the one --detail sets
};

// Declares --detail and --compactness, the automatic labeller's options.
void add_auto_label_options(CLI::App& app, LabelSource& source);

// Declares --plain: the labels files the command writes without their comment line.
void add_plain_labels_option(CLI::App& app, bool& plain);
LabelsHeader labels_header(bool plain);

// The labeller's options: --compactness overrides the compactness --detail sets.
AutoLabelOptions auto_label_options(const LabelSource& source);

std::vector<int> labels_from_source(const LabelSource& source, const PolygonMesh& mesh);

// Prints one line per orientation problem to stderr; returns whether any.
bool warn_about_orientation(const PolygonMesh& mesh, const std::vector<int>& labels, bool flipped);

}  // namespace polycube
