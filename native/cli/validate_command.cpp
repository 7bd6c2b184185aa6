// `polycube validate IN --labels FILE|auto|nearest [--detail D] [--compactness W] [--flip-labels] [--json]`
#include <algorithm>
#include <cstdio>

#include "cli/arguments.h"
#include "cli/commands.h"
#include "cli/flush_stdout.h"
#include "cli/label_source.h"
#include "labeller/auto_labels.h"
#include "labels/axis.h"
#include "labels/orientation.h"
#include "labels/validate_labels.h"
#include "io/labels_report.h"
#include "io/read_mesh.h"

namespace polycube {

namespace {

void print_faces(const std::vector<int>& faces) {
  const size_t shown = std::min<size_t>(faces.size(), 12);
  for (size_t k = 0; k < shown; ++k) std::printf(" %d", faces[k]);
  if (shown < faces.size()) std::printf(" ... (%zu more)", faces.size() - shown);
  std::printf("\n");
}

}  // namespace

int validate_command(const std::vector<std::string>& args) {
  CLI::App app{"Checks the labels against the polycube conditions (every chart touches at least four\n"
               "others, no opposite labels side by side, three charts at every corner), lists every\n"
               "violation with its faces and checks the orientation; also whether flat charts can realise\n"
               "the labels: reversed charts (invalid), turning points and squeezed faces (they collapse).\n"
               "Exit status 0 when valid, 4 when not.",
               "polycube validate"};
  std::string input;
  LabelSource source;
  bool json_output = false;
  app.add_option("IN", input, "the mesh (.off, .obj, .ply)")->required()->type_name("");
  app.add_option("--labels", source.labels,
                 "FILE: one label per face (0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = nearest);\n"
                 "auto: the automatic labeller; nearest: the axis nearest each normal")
      ->required()
      ->type_name("FILE|auto|nearest");
  add_auto_label_options(app, source);
  app.add_flag("--flip-labels", source.flip, "turn every label to its opposite (labels made for the other winding)");
  app.add_flag("--json", json_output, "print the result as JSON (violations with all their faces)");
  if (!parse_arguments(app, args)) return 0;

  const PolygonMesh mesh = read_mesh(input);
  const std::vector<int> labels = labels_from_source(source, mesh);
  const LabelValidation validation = validate_labels(mesh, labels);
  const Orientation orient = orientation(mesh, &labels);

  if (json_output) {
    Json json = {{"faces", mesh.faces.count()}};
    add_validation(json, validation);
    add_orientation(json["orientation"] = Json::object(), orient, true);
    print_line(json_text(json));
  } else {
    warn_about_orientation(mesh, labels, source.flip);
    std::printf("%d faces, %d charts, %d chart boundaries, %d corners", mesh.faces.count(), validation.charts,
                validation.boundaries, validation.corners);
    if (validation.unlabelled_faces > 0) std::printf(", %d unlabelled faces (judged by nearest axis)",
                                                     validation.unlabelled_faces);
    std::printf("\n");
    for (const LabelViolation& v : validation.violations) {
      std::printf("%s: chart %d (%s", violation_kind_name(v.kind), v.chart, kLabelNames[v.label]);
      switch (v.kind) {
        case ViolationKind::kTooFewNeighbours: std::printf(") touches %zu charts;", v.others.size()); break;
        case ViolationKind::kOppositeNeighbours: std::printf(") touches chart %d;", v.others[0]); break;
        case ViolationKind::kCornerTooManyCharts:
          std::printf(") and %zu more charts meet at vertex %d;", v.others.size(), v.vertex);
          break;
        case ViolationKind::kReversedChart: std::printf(") points away from its axis;"); break;
        case ViolationKind::kTurningPoint:
          std::printf(") meets chart %d along a boundary that doubles back;", v.others[0]);
          break;
        case ViolationKind::kSqueezedFaces: std::printf(") has %zu faces flat charts squeeze onto a line;", v.faces.size()); break;
      }
      std::printf(" faces");
      print_faces(v.faces);
    }
    std::printf("%s: %zu violation%s\n",
                validation.realisable() ? "valid" : validation.valid() ? "valid, not realisable without collapse" : "invalid",
                validation.violations.size(), validation.violations.size() == 1 ? "" : "s");
  }
  return validation.valid() ? 0 : 4;
}

}  // namespace polycube
