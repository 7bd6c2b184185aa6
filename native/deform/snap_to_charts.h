// A shape put on the planes of charts it nearly fits: per axis, the vertices
// that share a chart plane (ChartPlanes::current_unknowns) take the median of their
// coordinates, every other coordinate stays.
//
// Why the median: a polycube of labels that differ on a few faces (stage 8's
// further runs, docs/design.md section 2.6) has every chart plane but
// those faces' vertices in place already; the median keeps the plane where
// most of its vertices stand, where a mean would move the whole chart for
// a few vertices.
#pragma once

#include "deform/chart_planes.h"
#include "mesh/mesh.h"

namespace polycube {

Vertices snap_to_charts(const Vertices& x, const ChartPlanes& planes);

}  // namespace polycube
