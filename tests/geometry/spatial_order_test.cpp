// SPDX-License-Identifier: MIT
#include "tessera/geometry/spatial_order.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <random>
#include <vector>

#include "tessera/geometry/triangle_mesh.h"

namespace {

// Sum of the distances between consecutive columns of `points` in `order`.
double path_length(const Eigen::MatrixXd& points, const std::vector<int>& order) {
  double length = 0.0;
  for (std::size_t k = 1; k < order.size(); ++k) {
    length += (points.col(order[k]) - points.col(order[k - 1])).norm();
  }
  return length;
}

// A 32×32 grid of spacing h, in shuffled order, on the plane z = x + y.
Eigen::MatrixXd shuffled_grid(int side, double h) {
  std::vector<int> cells(static_cast<std::size_t>(side * side));
  std::iota(cells.begin(), cells.end(), 0);
  std::shuffle(cells.begin(), cells.end(), std::mt19937(7));
  Eigen::MatrixXd points(3, side * side);
  for (int k = 0; k < side * side; ++k) {
    const double x = h * (cells[k] % side);
    const double y = h * (cells[k] / side);
    points.col(k) << x, y, x + y;
  }
  return points;
}

}  // namespace

// A Hilbert curve through a grid steps from cell to neighbouring cell but for a few longer
// steps: its path is within a small factor of the shortest (N − 1 steps of h·√3 on this plane),
// where the shuffled order's is about N/3 of the grid's width each.
TEST(SpatialOrder, HilbertOrderWalksAGridByNeighbours) {
  const int side = 32;
  const double h = 0.1;
  const Eigen::MatrixXd points = shuffled_grid(side, h);
  const std::vector<int> order = tessera::hilbert_order(points);
  ASSERT_EQ(order.size(), static_cast<std::size_t>(side * side));
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  for (int k = 0; k < side * side; ++k) {
    ASSERT_EQ(sorted[k], k);  // a permutation
  }
  std::vector<int> identity(order.size());
  std::iota(identity.begin(), identity.end(), 0);
  const double shortest = (side * side - 1) * h * std::sqrt(2.0);
  EXPECT_LT(path_length(points, order), 1.5 * shortest);
  EXPECT_GT(path_length(points, identity), 10.0 * shortest);
  EXPECT_EQ(tessera::hilbert_order(points), order);  // deterministic
}

// In R^n (n > 3) the curve runs through the mesh's principal view: a plane embedded in R^12
// along two oblique directions is ordered as well as in R^3.
TEST(SpatialOrder, SpatiallyOrderedVerticesOfAMeshInRn) {
  const int side = 24;
  const double h = 0.05;
  const Eigen::MatrixXd grid = shuffled_grid(side, h);
  Eigen::MatrixXd directions = Eigen::MatrixXd::Zero(12, 2);
  for (int i = 0; i < 12; ++i) {
    directions(i, 0) = std::cos(0.3 * i);
    directions(i, 1) = std::sin(0.7 * i + 0.2);
  }
  const Eigen::MatrixXd points = directions * grid.topRows(2);
  tessera::TriangleMesh mesh(12);
  for (int k = 0; k < points.cols(); ++k) {
    mesh.add_vertex(points.col(k));
  }
  std::vector<int> vertices(static_cast<std::size_t>(points.cols()));
  std::iota(vertices.begin(), vertices.end(), 0);
  const std::vector<int> ordered = tessera::spatially_ordered(mesh, vertices);
  ASSERT_EQ(ordered.size(), vertices.size());
  // Each step of the grid is at most h times the longer direction's length in R^12. The view
  // shows the grid sheared (the two directions are not orthogonal), so the curve steps between
  // lattice neighbours less often than on a square grid: measured 2.6 such steps on average,
  // against 12 for the shuffled order.
  const double step = h * std::max(directions.col(0).norm(), directions.col(1).norm());
  EXPECT_LT(path_length(points, ordered), 3.5 * (points.cols() - 1) * step);
  EXPECT_GT(path_length(points, vertices), 3.0 * path_length(points, ordered));
  // A subset keeps its members.
  const std::vector<int> some = {5, 17, 3, 400, 99};
  std::vector<int> some_ordered = tessera::spatially_ordered(mesh, some);
  std::sort(some_ordered.begin(), some_ordered.end());
  EXPECT_EQ(some_ordered, (std::vector<int>{3, 5, 17, 99, 400}));
}

// A vertex with a coordinate that is not finite has no place on the curve: it comes last, and
// the others are still ordered (no comparison with NaN reaches the sort).
TEST(SpatialOrder, VerticesThatAreNotFiniteComeLast) {
  const Eigen::MatrixXd grid = shuffled_grid(8, 0.1);
  tessera::TriangleMesh mesh(3);
  for (int k = 0; k < grid.cols(); ++k) {
    mesh.add_vertex(grid.col(k));
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const int bad = mesh.add_vertex(Eigen::Vector3d(nan, 0.0, 1.0));
  const int infinite =
      mesh.add_vertex(Eigen::Vector3d(0.0, std::numeric_limits<double>::infinity(), 1.0));
  std::vector<int> vertices(static_cast<std::size_t>(mesh.vertex_count()));
  std::iota(vertices.begin(), vertices.end(), 0);
  std::swap(vertices[0], vertices[static_cast<std::size_t>(bad)]);  // first in the given order
  const std::vector<int> ordered = tessera::spatially_ordered(mesh, vertices);
  ASSERT_EQ(ordered.size(), vertices.size());
  EXPECT_EQ(ordered[ordered.size() - 2], bad);
  EXPECT_EQ(ordered.back(), infinite);
  std::vector<int> finite(ordered.begin(), ordered.end() - 2);
  EXPECT_LT(path_length(grid, finite), 1.5 * (grid.cols() - 1) * 0.1 * std::sqrt(2.0));
}
