#include "cli/label_source.h"

#include <cstdio>

#include "cli/arguments.h"
#include "labeller/auto_labels.h"
#include "labels/nearest_labels.h"
#include "labels/orientation.h"
#include "io/labels_io.h"

namespace polycube {

AutoLabelOptions auto_label_options(const Arguments& arguments) {
  AutoLabelOptions options = AutoLabelOptions::with_detail(arguments.get_double("detail", 0.5, 0.0));
  options.compactness = arguments.get_double("compactness", options.compactness, 0.0);
  return options;
}

std::vector<int> labels_from_source(const std::string& source, const PolygonMesh& mesh,
                                    const AutoLabelOptions& options, bool flip) {
  std::vector<int> labels;
  if (source == "nearest") {
    labels = nearest_labels(mesh);
  } else if (source == "auto") {
    labels = auto_labels(mesh, options);
  } else {
    labels = read_labels(source, mesh.faces.count());
  }
  return flip ? flip_labels(labels) : labels;
}

bool warn_about_orientation(const PolygonMesh& mesh, const std::vector<int>& labels, bool flipped) {
  const Orientation o = orientation(mesh, &labels);
  bool any = false;
  if (!o.orientable) {
    std::fprintf(stderr, "warning: the mesh is not orientable (like a Moebius strip): no winding makes "
                         "every face point outward, so some labels cannot be met\n");
    any = true;
  } else if (!o.consistent) {
    std::fprintf(stderr, "warning: the faces are wound inconsistently (%d edges run the same way in both faces)\n",
                 o.inconsistent_edges);
    any = true;
  }
  if (o.inward()) {
    std::fprintf(stderr, "warning: %d of %d closed parts are wound inward (normals point inside)\n",
                 o.inward_components, o.closed_components);
    any = true;
  }
  if (o.labels_opposite) {
    std::fprintf(stderr, "warning: %.0f%% of the area faces away from its label: labels made for the other "
                         "winding? %s\n", 100.0 * o.area_against_labels,
                 flipped ? "(after --flip-labels)" : "try --flip-labels");
    any = true;
  }
  return any;
}

}  // namespace polycube
