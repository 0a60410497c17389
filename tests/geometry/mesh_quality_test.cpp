// SPDX-License-Identifier: MIT
// Angles in R^n: the smallest angle of a triangle from its side lengths (Kahan's formula) agrees
// with the corner angles from the vectors, and stays accurate for needles where the law of
// cosines does not.
#include "tessera/geometry/mesh_quality.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace {

double smallest_corner_angle(const Eigen::VectorXd& a, const Eigen::VectorXd& b,
                             const Eigen::VectorXd& c) {
  return std::min({tessera::corner_angle(a, b, c), tessera::corner_angle(b, c, a),
                   tessera::corner_angle(c, a, b)});
}

TEST(MinAngle, FromSidesEqualsTheSmallestCornerAngleInRn) {
  std::srand(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 3 + trial % 20;
    const Eigen::VectorXd a = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd b = Eigen::VectorXd::Random(n);
    const Eigen::VectorXd c = Eigen::VectorXd::Random(n);
    const double expected = smallest_corner_angle(a, b, c);
    const double from_sides =
        tessera::min_angle_of_sides((b - a).norm(), (c - b).norm(), (a - c).norm());
    EXPECT_NEAR(from_sides, expected, 1e-12 * (1.0 + expected)) << trial;
    // The order of the sides does not matter.
    EXPECT_DOUBLE_EQ(tessera::min_angle_of_sides((a - c).norm(), (b - a).norm(), (c - b).norm()),
                     from_sides);
  }
}

TEST(MinAngle, FromSidesIsExactForKnownTriangles) {
  EXPECT_NEAR(tessera::min_angle_of_sides(1.0, 1.0, 1.0), std::numbers::pi / 3.0, 1e-15);
  EXPECT_NEAR(tessera::min_angle_of_sides(3.0, 4.0, 5.0), std::atan2(3.0, 4.0), 1e-15);
  // A needle: apex angle 1e-9 between two unit sides; the opposite side is 2 sin(5e-10).
  const double needle = 1e-9;
  EXPECT_NEAR(tessera::min_angle_of_sides(1.0, 1.0, 2.0 * std::sin(0.5 * needle)), needle,
              1e-15 * needle + 1e-24);
}

TEST(MinAngle, FromSidesIsZeroForDegenerateTriangles) {
  EXPECT_EQ(tessera::min_angle_of_sides(1.0, 2.0, 3.0), 0.0);  // collinear
  EXPECT_EQ(tessera::min_angle_of_sides(0.0, 1.0, 1.0), 0.0);  // two corners coincide
  EXPECT_EQ(tessera::min_angle_of_sides(0.0, 0.0, 0.0), 0.0);
  EXPECT_EQ(tessera::min_angle_of_sides(1.0, 1.0, 3.0), 0.0);  // no such triangle (rounding)
}

}  // namespace
