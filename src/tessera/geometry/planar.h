// SPDX-License-Identifier: MIT
// Vectors of a plane (the tangent-plane coordinates the methods work in, a picture's page).
#pragma once

#include <Eigen/Core>

namespace tessera {

/// The z component of (a, 0) × (b, 0): twice the signed area of the triangle (0, a, b),
/// positive when b lies counterclockwise of a.
inline double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a(0) * b(1) - a(1) * b(0);
}

}  // namespace tessera
