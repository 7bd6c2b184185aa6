// The point of a triangle nearest a given point, as barycentric weights of
// its corners: where a point on a surface lands on a nearby copy of it (the
// remesh's relaxation pulling vertices back onto the input, the coarse
// route's homes of fine vertices on the coarse mesh).
#pragma once

#include <Eigen/Core>

namespace polycube {

// Ericson, Real-Time Collision Detection 5.1.5: by the Voronoi region of the
// triangle abc that p falls in. On an edge or a corner the other weights are
// exactly zero, so a point carried by them stays on that edge; a degenerate
// triangle gives its first corner.
Eigen::Vector3d nearest_point_weights(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                      const Eigen::Vector3d& c);

}  // namespace polycube
