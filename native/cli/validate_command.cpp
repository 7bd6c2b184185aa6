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

const char* const kValidateUsage =
    "polycube validate IN.(off|obj|ply) --labels FILE|auto|nearest [--detail D] [--compactness W]\n"
    "                [--flip-labels] [--json]\n"
    "  Checks the labels against the polycube conditions (every chart touches at least four\n"
    "  others, no opposite labels side by side, three charts at every corner), lists every\n"
    "  violation with its faces and checks the orientation; also whether flat charts can realise\n"
    "  the labels: reversed charts (invalid), turning points and squeezed faces (they collapse).\n"
    "  Exit status 0 when valid, 4 when not.\n"
    "  --labels       FILE: one label per face (0..5 = +X,-X,+Y,-Y,+Z,-Z, -1 = nearest);\n"
    "                 auto: the automatic labeller; nearest: the axis nearest each normal\n"
    "  --detail, --compactness  for --labels auto, as in `polycube label`\n"
    "  --flip-labels  turn every label to its opposite (labels made for the other winding)\n"
    "  --json         print the result as JSON (violations with all their faces)\n";

namespace {

void print_faces(const std::vector<int>& faces) {
  const size_t shown = std::min<size_t>(faces.size(), 12);
  for (size_t k = 0; k < shown; ++k) std::printf(" %d", faces[k]);
  if (shown < faces.size()) std::printf(" ... (%zu more)", faces.size() - shown);
  std::printf("\n");
}

}  // namespace

int validate_command(const std::vector<std::string>& args) {
  const Arguments arguments(args, {"labels", "compactness", "detail"}, {"flip-labels", "json"});
  if (!arguments.has("labels")) throw Error("--labels FILE|auto|nearest is required");
  const bool flip = arguments.has("flip-labels");

  const PolygonMesh mesh = read_mesh(arguments.input());
  const std::vector<int> labels = labels_from_source(arguments.get("labels", ""), mesh, auto_label_options(arguments), flip);
  const LabelValidation validation = validate_labels(mesh, labels);
  const Orientation orient = orientation(mesh, &labels);

  if (arguments.has("json")) {
    Json json = {{"faces", mesh.faces.count()}};
    add_validation(json, validation);
    add_orientation(json["orientation"] = Json::object(), orient, true);
    print_line(json_text(json));
  } else {
    warn_about_orientation(mesh, labels, flip);
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
