// `polycube uv IN POLYCUBE --output OUT.obj [--labels FILE] [--relax] [--merge SLACK] [--no-pack]`
#include <cstdio>

#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/use_input.h"
#include "io/json.h"
#include "io/output_files.h"
#include "io/write_mesh.h"
#include "use/polycube_uv.h"
#include "use/uv_figures.h"

namespace polycube {

int uv_command(const std::vector<std::string>& args) {
  CLI::App app{"A UV map from the polycube: one island per chart, the polycube's positions in the chart's\n"
               "plane, one texel density, packed into the unit square. OUT.obj is IN with `vt` per corner.",
               "polycube uv"};
  UseInputPaths paths;
  std::string output;
  bool relax = false, no_pack = false;
  PolycubeUvOptions options;
  options.merge_slack = -1.0;
  add_use_inputs(app, paths);
  app.add_option("--output", output, "the mesh with its UV map, .obj")->required()->type_name("OUT.obj");
  app.add_flag("--relax", relax,
               "re-solve each island to keep the mesh's angles (least-squares conformal),\n"
               "keeping the polycube's islands and seams");
  app.add_option("--merge", options.merge_slack,
                 "(implies --relax) merge neighbouring islands whose union unfolds as a disk, longest seam\n"
                 "first, each merge raising angle distortion by at most SLACK (e.g. 0.01)")
      ->type_name("SLACK")
      ->check(number_at_least(0.0));
  app.add_flag("--no-pack", no_pack, "islands stay in their planes, overlapping");
  if (!parse_arguments(app, args)) return 0;
  const UseInput input = read_use_input(paths);
  options.pack = !no_pack;
  options.relax = relax || app.count("--merge");
  const PolycubeUv uv = polycube_uv(input.mesh, input.polycube, input.labels, options);
  OutputFiles outputs;  // in place only once the figures reached stdout too
  outputs.stage(output, obj_with_uvs_writer(output, input.mesh.vertices, input.mesh.faces, uv.uvs));
  const UvFigures figures = uv_figures(input.mesh, uv.uvs);
  const Json report = {{"islands", uv.islands},
                       {"angle_distortion", figures.angle_distortion},
                       {"area_distortion", figures.area_distortion},
                       {"collapsed_area", figures.collapsed_area},
                       {"flipped", figures.flipped},
                       {"seam_length", figures.seam_length}};
  print_line(json_text(report, -1));
  flush_stdout();
  outputs.commit();
  return 0;
}

}  // namespace polycube
