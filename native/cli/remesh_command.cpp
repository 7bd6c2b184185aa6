// `polycube remesh IN POLYCUBE --edge-length H --output OUT [--labels FILE]`
#include <cstdio>

#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/use_input.h"
#include "io/json.h"
#include "io/output_files.h"
#include "io/write_mesh.h"
#include "use/quad_remesh.h"

namespace polycube {

const char* const kRemeshUsage =
    "polycube remesh IN.(off|obj|ply) POLYCUBE.(off|obj|ply) --edge-length H --output OUT [--labels FILE]\n"
    "  An all-quad mesh of IN from its exact polycube: the polycube's planes snapped in order to a\n"
    "  grid of spacing H, its squares carried back onto IN. Irregular vertices only at polycube corners.\n"
    "  POLYCUBE       the mesh's polycube as `polycube deform --output` writes it\n"
    "  --edge-length  quad edge length, in IN's units (scaled by the polycube's own size)\n"
    "  --labels       the labels the solver ended with (default: read from the polycube's normals)\n";

int remesh_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"output", "labels", "edge-length"}, {}, 2);
  if (!arguments.has("output")) throw Error("--output OUT is required");
  if (!arguments.has("edge-length")) throw Error("--edge-length H is required");
  const UseInput input = read_use_input(arguments);
  QuadRemeshOptions options;
  options.edge_length = arguments.get_double("edge-length", 0.0, 0.0);
  const QuadRemesh remesh = quad_remesh(input.mesh, input.polycube, input.labels, options);
  const std::string output = arguments.get("output", "");
  OutputFiles outputs;  // in place only once the figures reached stdout too
  outputs.stage(output, mesh_file_bytes(output, remesh.mesh.vertices, remesh.mesh.faces));
  const Json figures = {{"vertices", remesh.mesh.vertices.rows()},
                        {"quads", remesh.mesh.faces.count()},
                        {"irregular_vertices", remesh.irregular_vertices},
                        {"open_edges", remesh.open_edges},
                        {"grid_spacing", remesh.grid_spacing}};
  print_line(json_text(figures, -1));
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
