// `polycube label IN --output LABELS.txt [--compactness W]`
#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/label_source.h"
#include "labels/auto_labels.h"
#include "labels/validate_labels.h"
#include "io/labels_io.h"
#include "io/read_mesh.h"

namespace polycube {

const char* const kLabelUsage =
    "polycube label IN.(off|obj|ply) --output LABELS.txt [--compactness W]\n"
    "  Labels every face automatically (graph cut over the six axes, then local repair of\n"
    "  what breaks the polycube conditions), writes one label per face and prints a summary.\n"
    "  --output       the labels file (0..5 = +X,-X,+Y,-Y,+Z,-Z), readable by --labels FILE\n"
    "  --compactness  weight of chart boundaries against fidelity to the normals (default 0.3):\n"
    "                 larger gives fewer, rounder charts\n";

int label_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"output", "compactness"});
  if (!arguments.has("output")) throw Error("--output LABELS.txt is required");
  AutoLabelOptions options;
  options.compactness = arguments.get_double("compactness", options.compactness, 0.0);
  const PolygonMesh mesh = read_mesh(arguments.input());
  const std::vector<int> labels = auto_labels(mesh, options);
  warn_about_orientation(mesh, labels, false);  // labels follow the winding: an inward mesh gets inward labels
  write_labels(arguments.get("output", ""), labels);
  const LabelValidation v = validate_labels(mesh, labels);
  std::printf("%d faces, %d charts, %d chart boundaries, %d corners, %zu violations%s\n", mesh.faces.count(),
              v.charts, v.boundaries, v.corners, v.violations.size(),
              v.valid() ? "" : " (run `polycube validate IN --labels LABELS.txt` to list them)");
  return 0;
}

}  // namespace polycube
