// deform() at any scale: the model moved into the unit box (unit_box.h),
// deformed there, and the positions (of the result and of every iteration
// the callback sees) moved back. The figures are scale-free already.
#include <algorithm>

#include "deform/deform.h"
#include "mesh/check_input.h"
#include "mesh/unit_box.h"

namespace polycube {

DeformResult deform(const PolygonMesh& input, const std::vector<int>& labels, const DeformOptions& options,
                    const IterationCallback& callback) {
  check_input(input, &labels);
  const UnitBoxMesh unit(input);
  const PolygonMesh& mesh = unit.mesh();
  IterationCallback unit_callback = callback;
  if (callback && !unit.box().identity())
    unit_callback = [&](int iteration, const Vertices& positions, const Figures& figures) {
      return callback(iteration, unit.box().from_unit(positions, mesh.vertices, input.vertices), figures);
    };
  DeformOptions unit_options = options;
  if (options.start.size() > 0) unit_options.start = unit.box().to_unit(options.start);
  DeformResult result = deform_in_unit_box(mesh, labels, unit_options, unit_callback);
  result.positions = unit.box().from_unit(result.positions, mesh.vertices, input.vertices);
  // The report never contradicts itself: a run that leaves faces above the
  // tolerance or folded is not converged, whatever the figures' rounding said.
  if (!result.unconverged_faces.empty() || !result.flipped_faces.empty() ||
      !(result.figures.normal_deviation_max_deg < options.tolerance_deg))
    result.converged = false;
  return result;
}

}  // namespace polycube
