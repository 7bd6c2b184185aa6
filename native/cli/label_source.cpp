#include "cli/label_source.h"

#include <cstdio>

#include "cli/arguments.h"
#include "labeller/auto_labels.h"
#include "labels/nearest_labels.h"
#include "labels/orientation.h"
#include "io/labels_io.h"

namespace polycube {

void add_auto_label_options(CLI::App& app, LabelSource& source) {
  app.add_option("--detail", source.detail, "0..1 (default 0.5): 0 gives a few large charts, 1 many small ones")
      ->type_name("D")
      ->check(number_at_least(0.0));
  app.add_option("--compactness", source.compactness,
                 "weight of chart boundaries against fidelity to the normals (default: set by\n"
                 "--detail, 0.3 at 0.5): larger gives fewer, rounder charts")
      ->type_name("W")
      ->check(number_at_least(0.0));
}

void add_plain_labels_option(CLI::App& app, bool& plain) {
  app.add_flag("--plain", plain,
               "labels files without their first line (a # comment stating the convention):\n"
               "nothing but one integer per face, for tools that read plain integers");
}

LabelsHeader labels_header(bool plain) { return plain ? LabelsHeader::kPlain : LabelsHeader::kComment; }

AutoLabelOptions auto_label_options(const LabelSource& source) {
  AutoLabelOptions options = AutoLabelOptions::with_detail(source.detail);
  if (source.compactness >= 0.0) options.compactness = source.compactness;
  return options;
}

std::vector<int> labels_from_source(const LabelSource& source, const PolygonMesh& mesh) {
  std::vector<int> labels;
  if (source.labels == "nearest") {
    labels = nearest_labels(mesh);
  } else if (source.labels == "auto") {
    labels = auto_labels(mesh, auto_label_options(source));
  } else {
    labels = read_labels(source.labels, mesh.faces.count());
  }
  return source.flip ? flip_labels(labels) : labels;
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
