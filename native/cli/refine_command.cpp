// `polycube refine IN --levels K [--scheme bilinear|loop|catmark] --output OUT [--labels FILE]`
#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/label_source.h"
#include "refine/refine.h"
#include "io/json.h"
#include "io/labels_io.h"
#include "io/output_files.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

namespace polycube {

int refine_command(const std::vector<std::string>& args) {
  CLI::App app{"Subdivides uniformly with OpenSubdiv so a coarse mesh can bend into a polycube.", "polycube refine"};
  std::string input, output, labels_path, scheme = "bilinear";
  int levels = 1;
  app.add_option("IN", input, "the mesh (.off, .obj, .ply)")->required()->type_name("");
  app.add_option("--levels", levels, "1..8; each level makes about four times the faces")
      ->required()
      ->type_name("K")
      ->check(whole_number_at_least(1));
  app.add_option("--scheme", scheme,
                 "bilinear (default): new vertices on the input surface; loop (triangles only)\n"
                 "or catmark (Catmull-Clark): smooth")
      ->type_name("bilinear|loop|catmark");
  app.add_option("--output", output, "the refined mesh, .obj, .off or .ply")->required()->type_name("OUT");
  app.add_option("--labels", labels_path, "per-face labels carried to the child faces, written to OUT.labels (--plain: no comment line)")
      ->type_name("FILE");
  bool plain = false;
  add_plain_labels_option(app, plain);
  if (!parse_arguments(app, args)) return 0;
  const RefineScheme refine_scheme = parse_refine_scheme(scheme);
  check_mesh_path(output);
  const PolygonMesh mesh = read_mesh(input);
  const std::vector<int> labels =
      app.count("--labels") ? read_labels(labels_path, mesh.faces.count()) : std::vector<int>{};
  const Refined refined = refine(mesh, labels, levels, refine_scheme);
  OutputFiles outputs;
  outputs.stage(output, mesh_file_writer(output, refined.mesh.vertices, refined.mesh.faces));
  if (!labels.empty()) outputs.stage(output + ".labels", labels_file_text(output + ".labels", refined.labels, labels_header(plain)));
  const Json figures = {{"vertices", refined.mesh.vertices.rows()}, {"faces", refined.mesh.faces.count()}};
  print_line(json_text(figures, -1));
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
