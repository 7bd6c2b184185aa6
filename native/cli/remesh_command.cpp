// `polycube remesh IN POLYCUBE --edge-length H --output OUT [--labels FILE] [--relax N]`
#include <cstdio>

#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/use_input.h"
#include "io/json.h"
#include "io/output_files.h"
#include "io/write_mesh.h"
#include "use/quad_remesh.h"

namespace polycube {

int remesh_command(const std::vector<std::string>& args) {
  CLI::App app{"An all-quad mesh of IN from its exact polycube: the polycube's planes snapped in order to a\n"
               "grid of spacing H, its squares carried back onto IN. Irregular vertices only at polycube corners.",
               "polycube remesh"};
  UseInputPaths paths;
  std::string output;
  QuadRemeshOptions options;
  add_use_inputs(app, paths);
  app.add_option("--edge-length", options.edge_length, "quad edge length, in IN's units (scaled by the polycube's own size)")
      ->required()
      ->type_name("H")
      ->check(number_at_least(0.0));
  app.add_option("--relax", options.relax_iterations,
                 "sweeps evening the vertices out on IN where the carried grid is stretched (default 10; 0: off)")
      ->type_name("N")
      ->check(whole_number_at_least(0));
  app.add_option("--output", output, "the quad mesh, .obj, .off or .ply")->required()->type_name("OUT");
  if (!parse_arguments(app, args)) return 0;
  check_mesh_path(output);
  const UseInput input = read_use_input(paths);
  const QuadRemesh remesh = quad_remesh(input.mesh, input.polycube, input.labels, options);
  OutputFiles outputs;  // in place only once the figures reached stdout too
  outputs.stage(output, mesh_file_writer(output, remesh.mesh.vertices, remesh.mesh.faces));
  const Json figures = {{"vertices", remesh.mesh.vertices.rows()},
                        {"quads", remesh.mesh.faces.count()},
                        {"irregular_vertices", remesh.irregular_vertices},
                        {"open_edges", remesh.open_edges},
                        {"boundary_loops", remesh.boundary_loops},
                        {"straightened_loops", remesh.straightened_loops},
                        {"grid_spacing", remesh.grid_spacing}};
  print_line(json_text(figures, -1));
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
