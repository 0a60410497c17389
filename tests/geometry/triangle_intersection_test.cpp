// SPDX-License-Identifier: MIT
#include "tessera/geometry/triangle_intersection.h"

#include <gtest/gtest.h>

#include <cmath>

namespace tessera {
namespace {

Eigen::Matrix<double, 2, 3> triangle(double x0, double y0, double x1, double y1, double x2,
                                     double y2) {
  Eigen::Matrix<double, 2, 3> t;
  t << x0, x1, x2, y0, y1, y2;
  return t;
}

// Rounding of the clipping: a few ulp of the squared coordinates (all O(1) here).
constexpr double kRounding = 1e-14;

TEST(TriangleIntersection, OfATriangleWithItselfIsTheTriangle) {
  const auto a = triangle(0, 0, 1, 0, 0, 1);
  const PlanarOverlap overlap = triangle_intersection(a, a);
  EXPECT_NEAR(overlap.area, 0.5, kRounding);
  EXPECT_NEAR(overlap.centroid.x(), 1.0 / 3, kRounding);
  EXPECT_NEAR(overlap.centroid.y(), 1.0 / 3, kRounding);
}

TEST(TriangleIntersection, DoesNotDependOnTheOrientationOfEither) {
  const auto a = triangle(0, 0, 2, 0, 0, 2);
  const auto b = triangle(1, 1, -1, 1, 1, -1);
  const auto b_reversed = triangle(1, 1, 1, -1, -1, 1);
  const double area = triangle_intersection(a, b).area;
  // a is x, y ≥ 0, x + y ≤ 2; b is x ≤ 1, y ≤ 1, x + y ≥ 0: a ∩ b is the unit square.
  EXPECT_NEAR(area, 1.0, kRounding);
  EXPECT_NEAR(triangle_intersection(a, b_reversed).area, area, kRounding);
  EXPECT_NEAR(triangle_intersection(b, a).area, area, kRounding);
}

TEST(TriangleIntersection, OfAContainedTriangleIsTheSmallerOne) {
  const auto big = triangle(-10, -10, 10, -10, 0, 10);
  const auto small = triangle(0, 0, 0.1, 0, 0, 0.1);
  const PlanarOverlap overlap = triangle_intersection(big, small);
  EXPECT_NEAR(overlap.area, 0.005, kRounding);
  EXPECT_NEAR(overlap.centroid.x(), 0.1 / 3, kRounding);
}

TEST(TriangleIntersection, IsZeroForTrianglesThatOnlyTouch) {
  const auto a = triangle(0, 0, 1, 0, 0, 1);
  EXPECT_LE(triangle_intersection(a, triangle(0, 0, -1, 0, 0, -1)).area, kRounding);  // vertex
  EXPECT_LE(triangle_intersection(a, triangle(1, 0, 0, 1, 1, 1)).area, kRounding);    // edge
  EXPECT_EQ(triangle_intersection(a, triangle(5, 5, 6, 5, 5, 6)).area, 0.0);          // apart
}

TEST(TriangleIntersection, IsZeroForADegenerateTriangle) {
  const auto a = triangle(0, 0, 1, 0, 0, 1);
  EXPECT_EQ(triangle_intersection(a, triangle(0, 0, 1, 1, 2, 2)).area, 0.0);
}

TEST(TriangleIntersection, OfAStarOfDavidIsTheHexagon) {
  // Two equilateral triangles of side 3 about the origin; their intersection is a regular
  // hexagon of side 1, area 3√3/2, centred at the origin.
  const double h = std::sqrt(3.0) / 2.0 * 3.0;  // height
  const auto up = triangle(-1.5, -h / 3, 1.5, -h / 3, 0, 2 * h / 3);
  const auto down = triangle(-1.5, h / 3, 0, -2 * h / 3, 1.5, h / 3);
  const PlanarOverlap overlap = triangle_intersection(up, down);
  EXPECT_NEAR(overlap.area, 3 * std::sqrt(3.0) / 2, kRounding);
  EXPECT_NEAR(overlap.centroid.norm(), 0.0, kRounding);
}

}  // namespace
}  // namespace tessera
