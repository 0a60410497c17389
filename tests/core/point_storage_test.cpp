// SPDX-License-Identifier: MIT
// PointStorage: the columns survive growth across the mapping threshold, shrinking, copies and
// moves; compaction in place keeps the right columns.
#include "tessera/core/point_storage.h"

#include <gtest/gtest.h>

#include "tessera/geometry/triangle_mesh.h"

namespace tessera {
namespace {

Eigen::VectorXd column_value(int n, int j) {
  Eigen::VectorXd x(n);
  for (int i = 0; i < n; ++i) {
    x(i) = 1000.0 * j + i;
  }
  return x;
}

// Enough columns of this n to cross kMappedBytes and grow the mapping (12 MB > 2 × 4 MiB).
constexpr int kDimension = 1000;
constexpr int kColumns = 1500;

TEST(PointStorage, ColumnsSurviveGrowthPastTheMappingThreshold) {
  PointStorage points(kDimension);
  for (int j = 0; j < kColumns; ++j) {
    points.push_back(column_value(kDimension, j));
  }
  ASSERT_EQ(points.size(), kColumns);
  ASSERT_GE(static_cast<std::size_t>(kColumns) * kDimension * sizeof(double),
            2 * PointStorage::kMappedBytes);
  for (int j = 0; j < kColumns; ++j) {
    ASSERT_EQ(points.column(j), column_value(kDimension, j)) << "column " << j;
  }
  EXPECT_EQ(points.matrix().cols(), kColumns);
  EXPECT_EQ(points.matrix()(7, 123), 123007.0);
}

TEST(PointStorage, ShrinkingAndGrowingAgainKeepsTheFirstColumns) {
  PointStorage points(kDimension);
  for (int j = 0; j < kColumns; ++j) {
    points.push_back(column_value(kDimension, j));
  }
  points.resize(10);  // far below the mapping threshold: the pages are given back
  ASSERT_EQ(points.size(), 10);
  for (int j = 0; j < 10; ++j) {
    EXPECT_EQ(points.column(j), column_value(kDimension, j));
  }
  for (int j = 10; j < kColumns; ++j) {
    points.push_back(column_value(kDimension, j));
  }
  EXPECT_EQ(points.column(kColumns - 1), column_value(kDimension, kColumns - 1));
  EXPECT_EQ(points.column(9), column_value(kDimension, 9));
}

TEST(PointStorage, CopiesAreDeepAndMovesHandOver) {
  for (const int columns : {3, kColumns}) {  // malloc'ed and mapped
    PointStorage points(kDimension);
    for (int j = 0; j < columns; ++j) {
      points.push_back(column_value(kDimension, j));
    }
    PointStorage copy = points;
    copy.column(0).setZero();
    EXPECT_EQ(points.column(0), column_value(kDimension, 0));
    const double* data = points.data();
    PointStorage moved = std::move(points);
    EXPECT_EQ(moved.data(), data);  // no copy
    EXPECT_EQ(moved.size(), columns);
    EXPECT_EQ(points.size(), 0);  // NOLINT(bugprone-use-after-move): the moved-from state
    points = copy;                // a moved-from storage can be assigned again
    EXPECT_EQ(points.column(columns - 1), column_value(kDimension, columns - 1));
  }
}

TEST(PointStorage, MoveColumnCompactsInPlace) {
  PointStorage points(4);
  for (int j = 0; j < 6; ++j) {
    points.push_back(column_value(4, j));
  }
  int kept = 0;
  for (int j = 0; j < 6; ++j) {
    if (j % 2 == 1) {
      points.move_column(j, kept++);
    }
  }
  points.resize(kept);
  ASSERT_EQ(points.size(), 3);
  EXPECT_EQ(points.column(0), column_value(4, 1));
  EXPECT_EQ(points.column(1), column_value(4, 3));
  EXPECT_EQ(points.column(2), column_value(4, 5));
}

TEST(PointStorage, WrongDimensionIsRefusedWithAMessage) {
  PointStorage points(3);
  try {
    points.push_back(Eigen::VectorXd::Zero(4));
    FAIL() << "no exception";
  } catch (const std::exception& error) {
    EXPECT_NE(std::string(error.what()).find("4 coordinates"), std::string::npos) << error.what();
  }
}

TEST(TriangleMesh, TakesItsPointsOverWithoutACopyAndTruncates) {
  PointStorage points(kDimension);
  for (int j = 0; j < kColumns; ++j) {
    points.push_back(column_value(kDimension, j));
  }
  const double* data = points.data();
  TriangleMesh mesh(std::move(points), {{0, 1, 2}});
  EXPECT_EQ(mesh.points().data(), data);
  EXPECT_EQ(mesh.vertex_count(), kColumns);
  mesh.add_vertex(column_value(kDimension, kColumns));
  mesh.truncate_vertices(3);
  EXPECT_EQ(mesh.vertex_count(), 3);
  EXPECT_EQ(mesh.point(2), column_value(kDimension, 2));
  EXPECT_THROW(mesh.truncate_vertices(4), std::exception);
}

}  // namespace
}  // namespace tessera
