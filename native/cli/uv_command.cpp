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

const char* const kUvUsage =
    "polycube uv IN.(off|obj|ply) POLYCUBE.(off|obj|ply) --output OUT.obj [--labels FILE] [--relax]\n"
    "            [--merge SLACK] [--no-pack]\n"
    "  A UV map from the polycube: one island per chart, the polycube's positions in the chart's\n"
    "  plane, one texel density, packed into the unit square. OUT.obj is IN with `vt` per corner.\n"
    "  POLYCUBE  the mesh's polycube as `polycube deform --output` writes it (same vertices, faces)\n"
    "  --labels  the labels the solver ended with (default: read from the polycube's normals);\n"
    "            a face turned away from its label is refused\n"
    "  --relax   re-solve each island to keep the mesh's angles (least-squares conformal),\n"
    "            keeping the polycube's islands and seams\n"
    "  --merge   (implies --relax) merge neighbouring islands whose union unfolds as a disk,\n"
    "            longest seam first, each merge raising angle distortion by at most SLACK (e.g. 0.01)\n"
    "  --no-pack islands stay in their planes, overlapping\n";

int uv_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"output", "labels", "merge"}, {"no-pack", "relax"}, 2);
  if (!arguments.has("output")) throw Error("--output OUT.obj is required");
  const UseInput input = read_use_input(arguments);
  PolycubeUvOptions options;
  options.pack = !arguments.has("no-pack");
  options.relax = arguments.has("relax") || arguments.has("merge");
  options.merge_slack = arguments.get_double("merge", -1.0, 0.0);
  const PolycubeUv uv = polycube_uv(input.mesh, input.polycube, input.labels, options);
  const std::string output = arguments.get("output", "");
  OutputFiles outputs;  // in place only once the figures reached stdout too
  outputs.stage(output, obj_with_uvs_bytes(output, input.mesh.vertices, input.mesh.faces, uv.uvs));
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
