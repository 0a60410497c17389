// SPDX-License-Identifier: MIT
// The Delaunay triangulation of scattered points is valid and has empty circumcircles.
#include "tessera/methods/planar/delaunay.h"

#include <gtest/gtest.h>

#include "methods/planar_test_support.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

TEST(PlanarDelaunay, RandomPointsGiveAValidTriangulationWithEmptyCircumcircles) {
  for (unsigned seed = 1; seed <= 10; ++seed) {
    const int n = 10 + 7 * static_cast<int>(seed);
    const Eigen::Matrix2Xd points = testing::random_points(n, seed);
    const PlanarTriangulation triangulation =
        delaunay_triangulation(points, Eigen::VectorXd::Zero(n));
    std::string why;
    EXPECT_TRUE(triangulation.is_valid(&why)) << "seed " << seed << ": " << why;
    EXPECT_EQ(triangulation.vertex_count(), n);
    // Euler: t = 2(N − 1) − N_B for a triangulation of the convex hull (Malcolm section 2).
    const int hull_vertices = static_cast<int>(triangulation.boundary_edges().size());
    EXPECT_EQ(triangulation.triangle_count(), 2 * (n - 1) - hull_vertices) << "seed " << seed;
    EXPECT_EQ(testing::count_circumcircle_violations(triangulation), 0) << "seed " << seed;
  }
}

TEST(PlanarDelaunay, KeepsTheValuesWithTheirPoints) {
  const Eigen::Matrix2Xd points = testing::random_points(20, 7);
  const Eigen::VectorXd values = points.row(0).transpose() * 3.0;
  const PlanarTriangulation triangulation = delaunay_triangulation(points, values);
  EXPECT_EQ(triangulation.points(), points);
  EXPECT_EQ(triangulation.values(), values);
}

TEST(PlanarDelaunay, ASquareGivesTwoTriangles) {
  Eigen::Matrix2Xd points(2, 4);
  points << 0, 1, 1, 0,  //
      0, 0, 1, 1;
  const PlanarTriangulation triangulation = delaunay_triangulation(points, Eigen::VectorXd());
  EXPECT_EQ(triangulation.triangle_count(), 2);
  EXPECT_EQ(triangulation.boundary_edges().size(), 4u);
  EXPECT_TRUE(triangulation.is_valid());
}

TEST(PlanarDelaunay, RefusesTooFewEqualOrCollinearPoints) {
  Eigen::Matrix2Xd two(2, 2);
  two << 0, 1, 0, 1;
  EXPECT_THROW(delaunay_triangulation(two, Eigen::VectorXd()), InvalidArgument);

  Eigen::Matrix2Xd collinear(2, 4);
  collinear << 0, 1, 2, 3,  //
      0, 1, 2, 3;
  try {
    delaunay_triangulation(collinear, Eigen::VectorXd());
    ADD_FAILURE() << "collinear points accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("one line"), std::string::npos) << error.what();
  }

  Eigen::Matrix2Xd duplicate(2, 4);
  duplicate << 0, 1, 0, 1,  //
      0, 0, 1, 0;
  try {
    delaunay_triangulation(duplicate, Eigen::VectorXd());
    ADD_FAILURE() << "equal points accepted";
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("points 1 and 3 are equal"), std::string::npos)
        << error.what();
  }
}

}  // namespace
}  // namespace tessera
