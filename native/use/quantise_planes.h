// The chart planes of one axis snapped to a grid of spacing h, in order: the
// k-th plane from the bottom goes to an integer step, every plane to its own
// step (no chart vanishes or crosses another), as close to its place as that
// allows (least total distance). The map between the polycube's coordinate
// and grid steps is piecewise linear and increasing through those pairs, so
// applied to each axis it takes the polycube onto its quantised polycube,
// one to one, planes onto grid planes.
#pragma once

#include <vector>

namespace polycube {

struct AxisGrid {
  std::vector<double> planes;  // distinct plane coordinates, increasing
  std::vector<long> steps;     // the grid step of each plane, increasing
  double h = 1.0;

  // Polycube coordinate -> grid units (a plane's coordinate gives exactly its step).
  double to_grid(double x) const;
  // Grid units -> polycube coordinate (a plane's step gives exactly its coordinate).
  double from_grid(double g) const;
};

// Inputs:
//   coordinates  the plane coordinate of every flat face of one axis (repeats welcome)
//   h            grid spacing (> 0)
//   tolerance    coordinates closer than this are one plane
AxisGrid quantise_planes(std::vector<double> coordinates, double h, double tolerance);

}  // namespace polycube
