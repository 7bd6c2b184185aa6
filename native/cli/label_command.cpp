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

int label_command(const std::vector<std::string>& args) {
  CLI::App app{"Labels every face automatically: straightens the shape so its normals gather on the axes,\n"
               "reads labels off it (graph cut over the six axes), repairs what breaks the polycube\n"
               "conditions and relabels faces flat charts would squeeze; writes one label per face and\n"
               "prints a summary.",
               "polycube label"};
  std::string input, output, straightened_path;
  LabelSource source;
  app.add_option("IN", input, "the mesh (.off, .obj, .ply)")->required()->type_name("");
  app.add_option("--output", output, "the labels file (0..5 = +X,-X,+Y,-Y,+Z,-Z), readable by --labels FILE")
      ->required()
      ->type_name("LABELS.txt");
  add_auto_label_options(app, source);
  bool plain = false;
  add_plain_labels_option(app, plain);
  app.add_option("--straightened", straightened_path,
                 "the straightened shape the labels were read from (same vertices and faces);\n"
                 "`polycube deform --start` can start from it")
      ->type_name("SHAPE");
  if (!parse_arguments(app, args)) return 0;
  const AutoLabelOptions options = auto_label_options(source);
  if (app.count("--straightened")) check_mesh_path(straightened_path);
  const PolygonMesh mesh = read_mesh(input);
  Vertices straightened;
  const std::vector<int> labels = auto_labels(mesh, options, &straightened);
  warn_about_orientation(mesh, labels, false);  // labels follow the winding: an inward mesh gets inward labels
  OutputFiles outputs;
  outputs.stage(output, labels_file_text(output, labels, labels_header(plain)));
  if (app.count("--straightened"))
    outputs.stage(straightened_path, mesh_file_writer(straightened_path, straightened, mesh.faces));
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
