// `polycube deform IN [--labels nearest|auto|FILE] [--flip-labels] [--iterations N] [--tolerance DEG]
//  [--variant robust|fixed|current] [--output OUT] [--output-labels LABELS.txt] [--report REPORT.json]`
#include <unistd.h>

#include <cstdio>
#include <future>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/label_source.h"
#include "cli/peak_memory.h"
#include "deform/deform.h"
#include "io/deform_report.h"
#include "io/labels_io.h"
#include "io/output_files.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"
#include "labeller/auto_labels.h"
#include "labels/nearest_labels.h"

namespace polycube {

int deform_command(const std::vector<std::string>& args) {
  CLI::App app{"Deforms the mesh into its polycube and prints the quality figures.", "polycube deform"};
  std::string input, start, output, output_labels, report_path, variant = variant_name(DeformOptions().variant);
  LabelSource source;
  DeformOptions options;
  app.add_option("IN", input, "the mesh (.off, .obj, .ply)")->required()->type_name("");
  app.add_option("--labels", source.labels,
                 "nearest (default): every face takes the axis nearest its normal;\n"
                 "auto: the automatic labeller (see `polycube label`; --detail, --compactness);\n"
                 "FILE: one label per face, 0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = nearest")
      ->type_name("nearest|auto|FILE");
  app.add_flag("--flip-labels", source.flip, "every label turned to its opposite: labels made for the other winding");
  add_auto_label_options(app, source);
  app.add_option("--iterations", options.iterations, "iteration limit (default 100)")
      ->type_name("N")
      ->check(whole_number_at_least(0));
  app.add_option("--tolerance", options.tolerance_deg,
                 "stop when every face is within DEG degrees of its axis (default 0.5; 0 = never)")
      ->type_name("DEG")
      ->check(number_at_least(0.0));
  app.add_option("--variant", variant,
                 "robust (default): never folds a face; fits each face's input shape, then makes\n"
                 "every chart exactly flat (slivers that would fold collapse; flat_iteration), or,\n"
                 "where the labels ask too much (flatten_attempts), goes on with the paper's step\n"
                 "and relabels faces that cannot reach their axis (relabelled_faces); faces still\n"
                 "above the tolerance: unconverged_faces.\n"
                 "fixed: the paper's method, Laplacian of the input, factorised once;\n"
                 "current: the paper's method, Laplacian rebuilt every iteration, as in the paper")
      ->type_name("robust|fixed|current");
  app.add_option("--start", start,
                 "a mesh with the same vertices and faces to start from\n"
                 "(`polycube label --straightened`)")
      ->type_name("SHAPE");
  app.add_option("--output", output, "the deformed mesh, .obj, .off or .ply (same vertices and faces)")
      ->type_name("OUT");
  app.add_option("--output-labels", output_labels,
                 "the labels the run ended with (the given ones, and any the\n"
                 "solver changed)")
      ->type_name("LABELS.txt");
  bool plain = false;
  add_plain_labels_option(app, plain);
  app.add_option("--report", report_path, "the figures and timings as JSON")->type_name("REPORT.json");
  bool keep_collapsed = false;
  app.add_flag("--no-relabel-collapsed", keep_collapsed,
               "robust: keep an exact result's collapsed faces; by default the run is repeated once with\n"
               "them relabelled, and kept when less collapses (relabelled_faces lists them)");
  app.add_flag("--rerun-from-result", options.rerun_from_result,
               "robust, from 100,000 triangles on: those further runs start from the result instead of the\n"
               "input, untangled only around the relabelled faces: several times faster, about as much\n"
               "collapsed, edge and area errors up to a sixth higher");
  app.add_option("--coarse-triangles", options.coarse_triangles,
                 "robust: a mesh of at least 4 times this many triangles is decimated to about this many\n"
                 "(its charts kept), deformed there and carried back; 0 deforms it at its own resolution")
      ->capture_default_str()
      ->check(CLI::NonNegativeNumber);
  bool first_run_only = false;
  app.add_flag("--no-last-resort", first_run_only,
               "robust: return the best state of a run that does not become an exact polycube; by default\n"
               "it is run once more, flattening accepted up to half the area collapsed (last_resort says so),\n"
               "then once more with faces of opposite labels that meet back to back relabelled (relabelled_faces)");
  bool unpolished = false;
  app.add_flag("--no-polish", unpolished,
               "robust: return an exact result as the run left it; by default its edge and area errors are\n"
               "lowered inside its flat charts, as one more iteration (polish_steps)");
  app.add_flag("--time-references", options.time_references,
               "also time one back-substitution and one measurement of this mesh\n"
               "(reference_seconds: what `make bench` states an iteration's cost against)");
  if (!parse_arguments(app, args)) return 0;
  options.variant = parse_variant(variant);
  options.relabel_collapsed = !keep_collapsed;
  options.last_resort = !first_run_only;
  options.polish = !unpolished;
  if (app.count("--output")) check_mesh_path(output);

  const PolygonMesh mesh = read_mesh(input);
  if (app.count("--start")) {
    const PolygonMesh shape = read_mesh(start);
    if (shape.vertices.rows() != mesh.vertices.rows() || shape.faces.indices != mesh.faces.indices)
      throw Error("--start must have the same vertices and faces as the input");
    options.start = shape.vertices;
  }
  const std::vector<int> labels = labels_from_source(source, mesh);
  // The orientation check only warns: on a thread of its own beside the
  // deformation (3 ms of B0's 0.16 s), its warnings printed when it ends. It
  // rejects what the deformation's own checks reject, with the same message.
  std::future<void> warned = std::async(std::launch::async, [&] {
    try {
      warn_about_orientation(mesh, labels, source.flip);
    } catch (const Error&) {
    }
  });

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
  warned.get();
  if (progress && result.iterations > 0) std::fprintf(stderr, "\n");

  Json json = deform_report(mesh, result, options);
  json["peak_mib"] = peak_resident_mib();
  const std::string report = json_text(json);
  OutputFiles outputs;
  if (app.count("--output")) outputs.stage(output, mesh_file_writer(output, result.positions, mesh.faces));
  if (app.count("--output-labels"))
    outputs.stage(output_labels, labels_file_text(output_labels, result.labels, labels_header(plain)));
  if (app.count("--report")) outputs.stage(report_path, report + "\n");
  print_line(report);
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
