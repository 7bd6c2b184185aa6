#include "deform/untangle_step.h"

#include "deform/chart_planes.h"
#include "deform/robust_run.h"
#include "deform/untangle_flat_charts.h"

namespace polycube {

UntangleStep untangle_step(RobustRun& run, const Vertices& flat, ChartPlanes& factored, const CollapseBound& bound,
                           UntangleStart start) {
  Deformation& d = run.d;
  const StageTimer timer(d.result.stages.untangle, d.set_apart);
  UntangleStep opened;
  // Newton's factorisations of the whole mesh are not held beside the
  // planes'; local rounds alone keep them, and the same charts afterwards
  // share those of the axes never collapsed (RobustRun::charts_like).
  const auto release = [&] {
    if (d.triangles().rows() < kUntangleNewtonFrom) return;
    factored.release();
    run.chart_factors.reset();
  };
  const UntangledCharts untangled =
      untangle_flat_charts(d.mesh.vertices, flat, d.triangles(), d.triangle_labels, kUntangleRounds,
                           kUntangleLocalShare, bound, UntangleMinimiser::automatic, d.options.stop_requested, release,
                           start);
  opened.rounds = untangled.rounds;
  if (untangled.refused) return opened;
  opened.positions = d.place(untangled.positions);
  opened.states = d.quality.face_states(opened.positions);
  opened.fold_free =
      opened.states.flipped_count == 0 &&
      d.quality.measure(opened.positions, opened.states, false).folded_edges <= d.result.input_folded_edges;
  return opened;
}

}  // namespace polycube
