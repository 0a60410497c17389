// SPDX-License-Identifier: MIT
// The intersection of two triangles in the plane: its area and centroid (convex clipping).
#pragma once

#include <Eigen/Core>

namespace tessera {

/// A convex polygon's area, centroid and perimeter; the centroid is meaningless if area == 0.
struct PlanarOverlap {
  double area = 0.0;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  double perimeter = 0.0;
  /// The largest distance from the origin of the plane to a vertex of the polygon.
  double reach = 0.0;
  /// area / perimeter: a lower bound on the polygon's inradius up to a factor 2 (equal to half
  /// the width of a thin strip), so the polygon stays non-empty when every edge moves inward
  /// by less than this. Thin overlaps (crossing needles) have a small area but a width that is
  /// not small against their own size; 0 if the polygon is empty.
  double width() const { return perimeter > 0.0 ? area / perimeter : 0.0; }
};

/// The intersection of the triangles a and b (columns are the corners, in either orientation),
/// by Sutherland–Hodgman clipping of a against the three edge half-planes of b, then the
/// shoelace formula. Triangles that only touch (a shared vertex or edge) give area 0 up to
/// rounding, a few ulp of the squared coordinates. A triangle of zero area gives area 0.
PlanarOverlap triangle_intersection(const Eigen::Matrix<double, 2, 3>& a,
                                    const Eigen::Matrix<double, 2, 3>& b);

}  // namespace tessera
