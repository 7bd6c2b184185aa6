// `polycube label IN --output LABELS.txt [--detail D] [--compactness W] [--straightened SHAPE]`
#include <algorithm>
#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/label_source.h"
#include "labeller/auto_labels.h"
#include "labels/validate_labels.h"
#include "io/labels_io.h"
#include "io/output_files.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

namespace polycube {

const char* const kLabelUsage =
    "polycube label IN.(off|obj|ply) --output LABELS.txt [--detail D] [--compactness W]\n"
    "               [--straightened SHAPE.(obj|off|ply)]\n"
    "  Labels every face automatically: straightens the shape so its normals gather on the axes,\n"
    "  reads labels off it (graph cut over the six axes), repairs what breaks the polycube\n"
    "  conditions and relabels faces flat charts would squeeze; writes one label per face and\n"
    "  prints a summary.\n"
    "  --detail       0..1 (default 0.5): 0 gives a few large charts, 1 many small ones\n"
    "  --output       the labels file (0..5 = +X,-X,+Y,-Y,+Z,-Z), readable by --labels FILE\n"
    "  --compactness  weight of chart boundaries against fidelity to the normals (default: set by\n"
    "                 --detail, 0.3 at 0.5): larger gives fewer, rounder charts\n"
    "  --straightened the straightened shape the labels were read from (same vertices and faces);\n"
    "                 `polycube deform --start` can start from it\n";

int label_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"output", "compactness", "detail", "straightened"});
  if (!arguments.has("output")) throw Error("--output LABELS.txt is required");
  const AutoLabelOptions options = auto_label_options(arguments);
  const PolygonMesh mesh = read_mesh(arguments.input());
  Vertices straightened;
  const std::vector<int> labels = auto_labels(mesh, options, &straightened);
  warn_about_orientation(mesh, labels, false);  // labels follow the winding: an inward mesh gets inward labels
  const std::string output = arguments.get("output", "");
  OutputFiles outputs;
  outputs.stage(output, labels_file_text(output, labels));
  if (arguments.has("straightened")) {
    const std::string path = arguments.get("straightened", "");
    outputs.stage(path, mesh_file_bytes(path, straightened, mesh.faces));
  }
  const LabelValidation v = validate_labels(mesh, labels);
  const size_t invalid = static_cast<size_t>(std::count_if(
      v.violations.begin(), v.violations.end(), [](const LabelViolation& x) { return makes_invalid(x.kind); }));
  std::printf("%d faces, %d charts, %d chart boundaries, %d corners, %zu violations, %zu realisability problems%s\n",
              mesh.faces.count(), v.charts, v.boundaries, v.corners, invalid, v.violations.size() - invalid,
              v.realisable() ? "" : " (run `polycube validate IN --labels LABELS.txt` to list them)");
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
