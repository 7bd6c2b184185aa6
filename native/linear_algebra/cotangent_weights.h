// Per-triangle cotangent weights: column k holds cot(angle at corner k) / 2,
// the weight of the edge opposite corner k.
//
// Cotangents are clamped to [-kMaxCotangent, kMaxCotangent]. An angle of about
// 0.06 degrees already gives 1000; larger values come only from needles and
// collapsed triangles, whose shape is rounding noise, and would make L
// arbitrarily ill-conditioned (a zero-area triangle would give inf, then NaN).
// Polycubes flatten some triangles on purpose, so the `current` variant meets
// them every iteration.
#pragma once

#include "mesh/mesh.h"

namespace polycube {

constexpr double kMaxCotangent = 1e3;

using CotangentWeights = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

CotangentWeights cotangent_weights(const Vertices& vertices, const Triangles& triangles);

}  // namespace polycube
