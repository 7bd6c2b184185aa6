// The chart planes of one axis snapped to a grid of spacing h, in order: every
// plane to a step of its own (no chart vanishes or crosses another), each gap
// between neighbouring planes to the whole number of steps nearest it (at
// least one). The gaps, not the planes' absolute places, are what the grid's
// spacing on the surface follows: a thin gap's extra step is not taken out of
// its neighbour, whose quads would stretch across it. The map between the
// polycube's coordinate and grid steps is piecewise linear and increasing
// through those pairs, so applied to each axis it takes the polycube onto its
// quantised polycube, one to one, planes onto grid planes.
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
