// SPDX-License-Identifier: MIT
// Marching triangles and chaining (methods/common/zero_set_curves): on small planar grids where
// the zero set of a linear or quadratic function is known, so every count below is exact.
#include "tessera/methods/common/zero_set_curves.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <set>

#include "tessera/core/error.h"

namespace tessera {
namespace {

// The grid of points (i, j), 0 ≤ i < columns, 0 ≤ j < rows, in R², each square split by its
// diagonal from (i, j) to (i + 1, j + 1); counterclockwise triangles.
TriangleMesh grid(int columns, int rows) {
  TriangleMesh mesh(2);
  for (int j = 0; j < rows; ++j) {
    for (int i = 0; i < columns; ++i) {
      mesh.add_vertex(Eigen::Vector2d(i, j));
    }
  }
  auto id = [columns](int i, int j) { return j * columns + i; };
  for (int j = 0; j + 1 < rows; ++j) {
    for (int i = 0; i + 1 < columns; ++i) {
      mesh.add_triangle(id(i, j), id(i + 1, j), id(i + 1, j + 1));
      mesh.add_triangle(id(i, j), id(i + 1, j + 1), id(i, j + 1));
    }
  }
  return mesh;
}

std::vector<double> values_of(const TriangleMesh& mesh, double (*f)(const Eigen::Vector2d&)) {
  std::vector<double> values;
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    values.push_back(f(mesh.point(v)));
  }
  return values;
}

double x_minus_one_and_a_half(const Eigen::Vector2d& p) { return p(0) - 1.5; }

// x = 1.5 on the 5×3 grid crosses the three horizontal edges and the two diagonals between the
// columns x = 1 and x = 2: one open chain of five crossings, from the bottom edge to the top.
TEST(ZeroSetCurves, AStraightLineAcrossAGridIsOneOpenChainThroughEveryCrossedEdgeInOrder) {
  const TriangleMesh mesh = grid(5, 3);
  const MeshTopology topology(mesh);
  const ZeroSetCurves curves =
      find_zero_set_curves(mesh, topology, values_of(mesh, x_minus_one_and_a_half));
  EXPECT_EQ(curves.crossing_count, 5);
  EXPECT_EQ(curves.evaluated_vertex_count, mesh.vertex_count());
  EXPECT_EQ(curves.processed_triangle_count, mesh.triangle_count());
  ASSERT_EQ(curves.chains.size(), 1u);
  EXPECT_FALSE(curves.chains[0].is_closed);
  ASSERT_EQ(curves.chains[0].crossings.size(), 5u);
  double previous_y = -1.0;
  const double direction =
      crossing_point(curves.crossings[static_cast<std::size_t>(curves.chains[0].crossings.back())],
                     mesh.points())(1) -
      crossing_point(curves.crossings[static_cast<std::size_t>(curves.chains[0].crossings.front())],
                     mesh.points())(1);
  ASSERT_NE(direction, 0.0);
  for (std::size_t k = 0; k < curves.chains[0].crossings.size(); ++k) {
    const ZeroSetCrossing& crossing =
        curves.crossings[static_cast<std::size_t>(curves.chains[0].crossings[k])];
    EXPECT_EQ(topology.edge(crossing.edge), crossing.vertices);
    const Eigen::VectorXd p = crossing_point(crossing, mesh.points());
    EXPECT_DOUBLE_EQ(p(0), 1.5);  // the function is linear: its interpolant is exact
    const double y = direction > 0 ? p(1) : -p(1);
    if (k > 0) {
      EXPECT_GT(y, previous_y);  // monotone along the chain: in order
    }
    previous_y = y;
  }
}

// A NaN at (2, 1) removes the crossings on its edges (the middle horizontal one and the lower
// diagonal): the curve ends at the triangles around it. What is left: the bottom edge's crossing
// alone and the upper diagonal joined to the top edge.
TEST(ZeroSetCurves, AVertexWithoutValueEndsTheChainsThatReachIt) {
  const TriangleMesh mesh = grid(5, 3);
  const MeshTopology topology(mesh);
  std::vector<double> values = values_of(mesh, x_minus_one_and_a_half);
  const int missing = 1 * 5 + 2;
  values[missing] = std::numeric_limits<double>::quiet_NaN();
  const ZeroSetCurves curves = find_zero_set_curves(mesh, topology, values);
  EXPECT_EQ(curves.crossing_count, 3);
  for (const ZeroSetCrossing& crossing : curves.crossings) {
    EXPECT_NE(crossing.vertices[0], missing);
    EXPECT_NE(crossing.vertices[1], missing);
  }
  ASSERT_EQ(curves.chains.size(), 2u);
  // Open chains first, isolated crossings last.
  EXPECT_FALSE(curves.chains[0].is_closed);
  EXPECT_EQ(curves.chains[0].crossings.size(), 2u);
  EXPECT_FALSE(curves.chains[1].is_closed);
  ASSERT_EQ(curves.chains[1].crossings.size(), 1u);
  const Eigen::VectorXd alone = crossing_point(
      curves.crossings[static_cast<std::size_t>(curves.chains[1].crossings[0])], mesh.points());
  EXPECT_DOUBLE_EQ(alone(0), 1.5);
  EXPECT_DOUBLE_EQ(alone(1), 0.0);
}

// (x − 2)² + (y − 2)² = 1.5 around the middle of a 5×5 grid: one closed chain; every crossing on
// two segments.
TEST(ZeroSetCurves, ACircleInsideTheGridIsOneClosedChain) {
  const TriangleMesh mesh = grid(5, 5);
  const MeshTopology topology(mesh);
  const ZeroSetCurves curves = find_zero_set_curves(mesh, topology, [&](int v) {
    const Eigen::Vector2d p = mesh.point(v);
    return (p - Eigen::Vector2d(2, 2)).squaredNorm() - 1.5;
  });
  ASSERT_EQ(curves.chains.size(), 1u);
  EXPECT_TRUE(curves.chains[0].is_closed);
  EXPECT_EQ(static_cast<int>(curves.chains[0].crossings.size()), curves.crossing_count);
  EXPECT_GE(curves.crossing_count, 8);
}

// Values are asked for lazily, once per vertex, at the corners of triangles reached: from a seed
// far from the curve nothing spreads; from a seed on it the whole curve is followed.
TEST(ZeroSetCurves, SeedsLimitTheEvaluationsAndACurveIsFollowedFromAnyTriangleOnIt) {
  const TriangleMesh mesh = grid(9, 9);
  const MeshTopology topology(mesh);
  std::vector<int> calls(static_cast<std::size_t>(mesh.vertex_count()), 0);
  auto value = [&](int v) {
    ++calls[static_cast<std::size_t>(v)];
    return mesh.point(v)(0) - 4.5;
  };
  ZeroSetOptions far;
  far.seed_triangles = std::vector<int>{0, 0, 1};  // at x ∈ [0, 1]; repeats are harmless
  const ZeroSetCurves none = find_zero_set_curves(mesh, topology, value, far);
  EXPECT_EQ(none.crossing_count, 0);
  EXPECT_EQ(none.evaluated_vertex_count, 4);
  EXPECT_EQ(none.processed_triangle_count, 2);

  std::fill(calls.begin(), calls.end(), 0);
  ZeroSetOptions on_curve;
  on_curve.seed_triangles = std::vector<int>{2 * (4 * 8 + 4)};  // square (4, 4), lower
  const ZeroSetCurves followed = find_zero_set_curves(mesh, topology, value, on_curve);
  EXPECT_EQ(followed.crossing_count, 9 + 8);  // 9 horizontal edges, 8 diagonals
  ASSERT_EQ(followed.chains.size(), 1u);
  EXPECT_EQ(followed.chains[0].crossings.size(), 17u);
  EXPECT_LT(followed.evaluated_vertex_count, mesh.vertex_count() / 2);
  for (const int count : calls) {
    EXPECT_LE(count, 1);
  }
}

// A skipped triangle on the curve cuts it in two open chains; it is counted.
TEST(ZeroSetCurves, ASkippedTriangleCutsTheCurve) {
  const TriangleMesh mesh = grid(5, 5);
  const MeshTopology topology(mesh);
  const std::vector<double> values = values_of(mesh, x_minus_one_and_a_half);
  ZeroSetOptions options;
  const int skipped = 2 * (2 * 4 + 1);  // square (1, 2), lower triangle: on the curve
  options.skip_triangle = [skipped](int t) { return t == skipped; };
  const ZeroSetCurves curves = find_zero_set_curves(mesh, topology, values, options);
  EXPECT_EQ(curves.skipped_triangle_count, 1);
  EXPECT_EQ(curves.crossing_count, 5 + 4);
  ASSERT_EQ(curves.chains.size(), 2u);
  EXPECT_FALSE(curves.chains[0].is_closed);
  EXPECT_FALSE(curves.chains[1].is_closed);
  EXPECT_EQ(curves.chains[0].crossings.size() + curves.chains[1].crossings.size(), 9u);
}

// Zero counts as positive: a vertex exactly on the line x = 1 with the rest of its column gives
// crossings only on the edges towards x = 0, never three in a triangle.
TEST(ZeroSetCurves, ZeroCountsAsPositive) {
  const TriangleMesh mesh = grid(3, 3);
  const MeshTopology topology(mesh);
  const ZeroSetCurves curves =
      find_zero_set_curves(mesh, topology, [&](int v) { return mesh.point(v)(0) - 1.0; });
  for (const ZeroSetCrossing& crossing : curves.crossings) {
    EXPECT_DOUBLE_EQ(crossing_point(crossing, mesh.points())(0), 1.0);
  }
  EXPECT_EQ(curves.crossing_count, 3 + 2);  // the edges from x = 0 to x = 1
  ASSERT_EQ(curves.chains.size(), 1u);
}

TEST(ZeroSetCurves, RefusesValuesOfTheWrongLengthAndSeedsOutOfRange) {
  const TriangleMesh mesh = grid(3, 3);
  const MeshTopology topology(mesh);
  EXPECT_THROW(find_zero_set_curves(mesh, topology, std::vector<double>(4, 1.0)), InvalidArgument);
  ZeroSetOptions options;
  options.seed_triangles = std::vector<int>{mesh.triangle_count()};
  EXPECT_THROW(find_zero_set_curves(mesh, topology, std::vector<double>(9, 1.0), options),
               InvalidArgument);
  const MeshTopology other(grid(4, 3));
  EXPECT_THROW(find_zero_set_curves(mesh, other, std::vector<double>(9, 1.0)), InvalidArgument);
}

}  // namespace
}  // namespace tessera
