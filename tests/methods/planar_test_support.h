// SPDX-License-Identifier: MIT
// Helpers shared by the planar tests: random point sets and the empty-circumcircle check.
#pragma once

#include <Eigen/Core>
#include <random>

#include "tessera/methods/planar/planar_triangulation.h"

namespace tessera::testing {

/// `count` points uniformly distributed in the unit square, reproducible from `seed`.
inline Eigen::Matrix2Xd random_points(int count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::Matrix2Xd points(2, count);
  for (int i = 0; i < count; ++i) {
    points(0, i) = uniform(generator);
    points(1, i) = uniform(generator);
  }
  return points;
}

/// In-circle determinant of d against the counter-clockwise triangle (a, b, c): > 0 when d is
/// strictly inside the circumcircle. Long double so that the check is sharper than the
/// triangulation it checks.
inline long double in_circle(const Eigen::Vector2d& a, const Eigen::Vector2d& b,
                             const Eigen::Vector2d& c, const Eigen::Vector2d& d) {
  const long double adx = a.x() - d.x();
  const long double ady = a.y() - d.y();
  const long double bdx = b.x() - d.x();
  const long double bdy = b.y() - d.y();
  const long double cdx = c.x() - d.x();
  const long double cdy = c.y() - d.y();
  return (adx * adx + ady * ady) * (bdx * cdy - cdx * bdy) -
         (bdx * bdx + bdy * bdy) * (adx * cdy - cdx * ady) +
         (cdx * cdx + cdy * cdy) * (adx * bdy - bdx * ady);
}

/// Number of (triangle, vertex) pairs with the vertex strictly inside the triangle's
/// circumcircle, beyond a relative 1e-12 (brute force, O(N·T)).
inline int count_circumcircle_violations(const PlanarTriangulation& triangulation) {
  int violations = 0;
  for (const Triangle& t : triangulation.triangles()) {
    const Eigen::Vector2d a = triangulation.point(t[0]);
    const Eigen::Vector2d b = triangulation.point(t[1]);
    const Eigen::Vector2d c = triangulation.point(t[2]);
    const double scale = std::pow((a - b).norm() + (b - c).norm() + (c - a).norm(), 4);
    for (int v = 0; v < triangulation.vertex_count(); ++v) {
      if (v == t[0] || v == t[1] || v == t[2]) {
        continue;
      }
      if (in_circle(a, b, c, triangulation.point(v)) > 1e-12 * scale) {
        ++violations;
      }
    }
  }
  return violations;
}

}  // namespace tessera::testing
