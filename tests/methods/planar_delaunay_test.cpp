// SPDX-License-Identifier: MIT
// The Delaunay triangulation of scattered points is valid and has empty circumcircles.
#include "tessera/methods/planar/delaunay.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <iostream>
#include <numeric>
#include <random>
#include <vector>

#include "methods/planar_test_support.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

int count_edges(const PlanarTriangulation& triangulation) {
  return static_cast<int>(triangulation.edges().size());
}

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

// Checks the input-order rule on every exactly cocircular interior edge: the diagonal avoids
// the quadrilateral's node with the largest index. Returns the number of such edges.
int expect_input_order_rule(const PlanarTriangulation& triangulation) {
  int cocircular = 0;
  for (int t = 0; t < triangulation.triangle_count(); ++t) {
    for (int k = 0; k < 3; ++k) {
      if (triangulation.neighbour(t, k) < t) {
        continue;  // boundary, or seen from the other side
      }
      const EdgeQuadrilateral q = triangulation.quadrilateral(t, k);
      // Integer coordinates: the long double in-circle determinant is exact here.
      if (testing::in_circle(triangulation.point(q.a), triangulation.point(q.b),
                             triangulation.point(q.c), triangulation.point(q.d)) != 0) {
        continue;
      }
      ++cocircular;
      const int last = std::max({q.a, q.b, q.c, q.d});
      EXPECT_TRUE(last == q.c || last == q.d)
          << "edge " << q.a << "–" << q.b << " of the cocircular quadrilateral with " << q.c << ", "
          << q.d << " touches the last node " << last;
    }
  }
  return cocircular;
}

TEST(PlanarDelaunay, ASquaresDiagonalAvoidsItsLastNode) {
  // The same square with the corners numbered so that each diagonal in turn avoids node 3.
  for (const bool last_on_first_diagonal : {false, true}) {
    Eigen::Matrix2Xd points(2, 4);
    if (last_on_first_diagonal) {
      points << 0, 1, 0, 1,  // node 3 = (1, 1): the diagonal must be (1, 0)–(0, 1)
          0, 0, 1, 1;
    } else {
      points << 0, 1, 1, 0,  // node 3 = (0, 1): the diagonal must be (0, 0)–(1, 1)
          0, 0, 1, 1;
    }
    DelaunaySummary summary;
    const PlanarTriangulation triangulation =
        delaunay_triangulation(points, Eigen::VectorXd(), &summary);
    EXPECT_EQ(summary.cocircular_edges, 1);
    EXPECT_EQ(expect_input_order_rule(triangulation), 1);
    EXPECT_EQ(count_edges(triangulation), 5);
  }
}

TEST(PlanarDelaunay, GridsAndCirclesFollowTheInputOrderRuleWhateverTheNumbering) {
  // A 5×5 grid (16 cocircular cells) and the 12 integer points on x² + y² = 25 (all on one
  // circle), each under several numberings: always Delaunay, and every cocircular edge
  // follows the rule.
  Eigen::Matrix2Xd grid(2, 25);
  for (int i = 0; i < 25; ++i) {
    grid.col(i) << i % 5, i / 5;
  }
  Eigen::Matrix2Xd circle(2, 12);
  circle << 5, 4, 3, 0, -3, -4, -5, -4, -3, 0, 3, 4,  //
      0, 3, 4, 5, 4, 3, 0, -3, -4, -5, -4, -3;
  int rule_swaps = 0;
  for (const Eigen::Matrix2Xd& points : {grid, circle}) {
    for (unsigned seed = 0; seed < 6; ++seed) {
      std::vector<int> order(points.cols());
      std::iota(order.begin(), order.end(), 0);
      std::shuffle(order.begin(), order.end(), std::mt19937(seed));
      Eigen::Matrix2Xd shuffled(2, points.cols());
      for (int i = 0; i < points.cols(); ++i) {
        shuffled.col(i) = points.col(order[i]);
      }
      DelaunaySummary summary;
      const PlanarTriangulation triangulation =
          delaunay_triangulation(shuffled, Eigen::VectorXd(), &summary);
      ASSERT_TRUE(triangulation.is_valid());
      EXPECT_EQ(testing::count_circumcircle_violations(triangulation), 0) << "seed " << seed;
      EXPECT_EQ(expect_input_order_rule(triangulation), summary.cocircular_edges);
      // Every interior edge of a grid of unit squares, or of a polygon inscribed in a circle,
      // is cocircular: grid 16 cells, circle 12 − 3 diagonals.
      EXPECT_EQ(summary.cocircular_edges, points.cols() == 25 ? 16 : 9) << "seed " << seed;
      rule_swaps += summary.rule_swaps;
    }
  }
  // CGAL's own choice follows another rule, so the input-order rule had work to do.
  EXPECT_GT(rule_swaps, 0);
  std::cout << "swaps by the input-order rule: " << rule_swaps << "\n";
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
