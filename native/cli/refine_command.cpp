// `polycube refine IN --levels K [--scheme bilinear|loop|catmark] --output OUT [--labels FILE]`
#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "refine/refine.h"
#include "io/json.h"
#include "io/labels_io.h"
#include "io/output_files.h"
#include "io/read_mesh.h"
#include "io/write_mesh.h"

namespace polycube {

const char* const kRefineUsage =
    "polycube refine IN.(off|obj|ply) --levels K [--scheme bilinear|loop|catmark] --output OUT\n"
    "                [--labels FILE]\n"
    "  Subdivides uniformly with OpenSubdiv so a coarse mesh can bend into a polycube.\n"
    "  --levels  1..8; each level makes about four times the faces\n"
    "  --scheme  bilinear (default): new vertices on the input surface; loop (triangles only)\n"
    "            or catmark (Catmull-Clark): smooth\n"
    "  --labels  per-face labels carried to the child faces, written to OUT.labels\n";

int refine_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"levels", "scheme", "output", "labels"});
  if (!arguments.has("output")) throw Error("--output is required");
  if (!arguments.has("levels")) throw Error("--levels is required");
  const int levels = arguments.get_int("levels", 1, 1);
  const RefineScheme scheme = parse_refine_scheme(arguments.get("scheme", "bilinear"));
  const PolygonMesh mesh = read_mesh(arguments.input());
  const std::vector<int> labels =
      arguments.has("labels") ? read_labels(arguments.get("labels", ""), mesh.faces.count()) : std::vector<int>{};
  const Refined refined = refine(mesh, labels, levels, scheme);
  const std::string output = arguments.get("output", "");
  OutputFiles outputs;
  outputs.stage(output, mesh_file_bytes(output, refined.mesh.vertices, refined.mesh.faces));
  if (!labels.empty()) outputs.stage(output + ".labels", labels_file_text(output + ".labels", refined.labels));
  const Json figures = {{"vertices", refined.mesh.vertices.rows()}, {"faces", refined.mesh.faces.count()}};
  print_line(json_text(figures, -1));
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
