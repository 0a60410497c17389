// SPDX-License-Identifier: MIT
// Diagonal swaps keep a planar triangulation valid and are refused where they would not.
#include "tessera/methods/planar/planar_triangulation.h"

#include <gtest/gtest.h>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// The unit square split by the diagonal 0–2: triangles (0, 1, 2) and (0, 2, 3).
PlanarTriangulation unit_square() {
  Eigen::Matrix2Xd points(2, 4);
  points << 0, 1, 1, 0,  //
      0, 0, 1, 1;
  return PlanarTriangulation(points, Eigen::Vector4d(0, 1, 2, 3), {{0, 1, 2}, {0, 2, 3}});
}

TEST(PlanarTriangulation, BuildsNeighboursAcrossTheDiagonal) {
  const PlanarTriangulation square = unit_square();
  EXPECT_TRUE(square.is_valid());
  EXPECT_EQ(square.neighbour(0, 2), 1);  // edge 2→0 of (0, 1, 2)
  EXPECT_EQ(square.neighbour(1, 0), 0);  // edge 0→2 of (0, 2, 3)
  EXPECT_EQ(square.edges().size(), 5u);
  EXPECT_EQ(square.boundary_edges().size(), 4u);
}

TEST(PlanarTriangulation, SwapReplacesTheDiagonalAndTwoSwapsRestoreIt) {
  PlanarTriangulation square = unit_square();
  const auto boundary = square.boundary_edges();
  ASSERT_TRUE(square.is_swap_valid(0, 2));
  square.swap(0, 2);
  std::string why;
  EXPECT_TRUE(square.is_valid(&why)) << why;
  EXPECT_EQ(square.boundary_edges(), boundary);
  const auto edges = square.edges();
  EXPECT_NE(std::find(edges.begin(), edges.end(), std::array<int, 2>{1, 3}), edges.end());
  EXPECT_EQ(std::find(edges.begin(), edges.end(), std::array<int, 2>{0, 2}), edges.end());
  ASSERT_TRUE(square.is_swap_valid(0, 2));  // the new diagonal is local edge 2
  square.swap(0, 2);
  EXPECT_TRUE(square.is_valid(&why)) << why;
  const auto restored = square.edges();
  EXPECT_NE(std::find(restored.begin(), restored.end(), std::array<int, 2>{0, 2}), restored.end());
}

TEST(PlanarTriangulation, RefusesToSwapBoundaryEdgesAndNonConvexQuadrilaterals) {
  PlanarTriangulation square = unit_square();
  EXPECT_FALSE(square.is_swap_valid(0, 0));  // boundary edge 0→1
  EXPECT_THROW(square.swap(0, 0), InvalidArgument);

  // A dart: vertex 3 is inside the triangle (0, 1, 2)'s side, so the quadrilateral 0, 1, 2, 3
  // is not convex at 3 and the other diagonal 1–3 would leave it.
  Eigen::Matrix2Xd points(2, 4);
  points << 0, 1, 0.2, 0.3,  //
      0, 0, 1, 0.3;
  PlanarTriangulation dart(points, Eigen::Vector4d::Zero(), {{0, 1, 3}, {1, 2, 3}});
  ASSERT_TRUE(dart.is_interior_edge(0, 1));
  EXPECT_FALSE(dart.is_swap_valid(0, 1));
  // A quadrilateral with three collinear corners is not strictly convex either.
  Eigen::Matrix2Xd flat(2, 4);
  flat << 0, 1, 2, 1,  //
      0, 0, 0, 1;
  PlanarTriangulation flat_corner(flat, Eigen::Vector4d::Zero(), {{0, 1, 3}, {1, 2, 3}});
  ASSERT_TRUE(flat_corner.is_interior_edge(0, 1));
  EXPECT_FALSE(flat_corner.is_swap_valid(0, 1));
}

TEST(PlanarTriangulation, RefusesClockwiseTrianglesAndNonManifoldEdges) {
  Eigen::Matrix2Xd points(2, 4);
  points << 0, 1, 1, 0,  //
      0, 0, 1, 1;
  EXPECT_THROW(PlanarTriangulation(points, Eigen::Vector4d::Zero(), {{0, 2, 1}}), InvalidArgument);
  EXPECT_THROW(PlanarTriangulation(points, Eigen::Vector4d::Zero(), {{0, 1, 2}, {0, 1, 3}}),
               InvalidArgument);
  EXPECT_THROW(PlanarTriangulation(points, Eigen::Vector3d::Zero(), {{0, 1, 2}}), InvalidArgument);
}

}  // namespace
}  // namespace tessera
