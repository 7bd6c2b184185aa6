// `polycube deform IN [--labels nearest|auto|FILE] [--flip-labels] [--iterations N] [--tolerance DEG]
//  [--variant robust|fixed|current] [--output OUT] [--output-labels LABELS.txt] [--report REPORT.json]`
#include <unistd.h>

#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/peak_memory.h"
#include "cli/label_source.h"
#include "labeller/auto_labels.h"
#include "deform/deform.h"
#include "labels/nearest_labels.h"
#include "io/deform_report.h"
#include "io/labels_io.h"
#include "io/output_files.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

namespace polycube {

const char* const kDeformUsage =
    "polycube deform IN.(off|obj|ply) [--labels nearest|auto|FILE] [--flip-labels] [--iterations N] [--tolerance DEG]\n"
    "                [--variant robust|fixed|current] [--output OUT.(obj|off|ply)] [--output-labels LABELS.txt]\n"
    "                [--start SHAPE] [--report REPORT.json]\n"
    "  Deforms the mesh into its polycube and prints the quality figures.\n"
    "  --labels      nearest (default): every face takes the axis nearest its normal;\n"
    "                auto: the automatic labeller (see `polycube label`; --detail D, --compactness W);\n"
    "                FILE: one label per face, 0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = nearest\n"
    "  --flip-labels every label turned to its opposite: labels made for the other winding\n"
    "  --iterations  iteration limit (default 100)\n"
    "  --tolerance   stop when every face is within DEG degrees of its axis (default 0.5; 0 = never)\n"
    "  --variant     robust (default): never folds a face; fits each face's input shape, then makes\n"
    "                every chart exactly flat (slivers that would fold collapse; flat_iteration), or,\n"
    "                where the labels ask too much (flatten_attempts), goes on with the paper's step\n"
    "                and relabels faces that cannot reach their axis (relabelled_faces); faces\n"
    "                still above the tolerance: unconverged_faces\n"
    "                fixed: the paper's method, Laplacian of the input, factorised once;\n"
    "                current: the paper's method, Laplacian rebuilt every iteration, as in the paper\n"
    "  --start       a mesh with the same vertices and faces to start from (`polycube label --straightened`)\n"
    "  --output      the deformed mesh (same vertices and faces as the input)\n"
    "  --output-labels  the labels the run ended with (the given ones, and any the solver changed)\n"
    "  --report      the figures and timings as JSON\n";

int deform_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"labels", "iterations", "tolerance", "variant", "output", "output-labels", "report", "compactness", "detail", "start"},
                            {"flip-labels"});
  DeformOptions options;
  options.iterations = arguments.get_int("iterations", options.iterations, 0);
  options.tolerance_deg = arguments.get_double("tolerance", options.tolerance_deg, 0.0);
  options.variant = parse_variant(arguments.get("variant", variant_name(options.variant)));

  const PolygonMesh mesh = read_mesh(arguments.input());
  if (arguments.has("start")) {
    const PolygonMesh start = read_mesh(arguments.get("start", ""));
    if (start.vertices.rows() != mesh.vertices.rows() || start.faces.indices != mesh.faces.indices)
      throw Error("--start must have the same vertices and faces as the input");
    options.start = start.vertices;
  }
  const std::string labels_source = arguments.get("labels", "nearest");
  const bool flip = arguments.has("flip-labels");
  const std::vector<int> labels = labels_from_source(
      labels_source, mesh, auto_label_options(arguments), flip);
  warn_about_orientation(mesh, labels, flip);

  // Progress only on a terminal: in logs and pipes it would be noise.
  const bool progress = isatty(fileno(stderr));
  IterationCallback show_progress;
  if (progress)
    show_progress = [](int iteration, const Vertices&, const Figures& f) {
      std::fprintf(stderr, "\riteration %4d: max deviation %8.3f deg, %d flipped   ", iteration,
                   f.normal_deviation_max_deg, f.flipped_faces);
      return true;
    };
  const DeformResult result = deform(mesh, labels, options, show_progress);
  if (progress && result.iterations > 0) std::fprintf(stderr, "\n");

  Json json = deform_report(mesh, result, options);
  json["peak_mib"] = peak_resident_mib();
  const std::string report = json_text(json);
  OutputFiles outputs;
  if (arguments.has("output")) {
    const std::string path = arguments.get("output", "");
    outputs.stage(path, mesh_file_bytes(path, result.positions, mesh.faces));
  }
  if (arguments.has("output-labels")) {
    const std::string path = arguments.get("output-labels", "");
    outputs.stage(path, labels_file_text(path, result.labels));
  }
  if (arguments.has("report")) outputs.stage(arguments.get("report", ""), report + "\n");
  print_line(report);
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
