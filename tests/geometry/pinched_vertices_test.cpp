// SPDX-License-Identifier: MIT
#include "tessera/geometry/pinched_vertices.h"

#include <gtest/gtest.h>

#include <algorithm>

namespace tessera {
namespace {

TEST(KeepLargestFans, LeavesAManifoldMeshAlone) {
  // A closed tetrahedron: every vertex has one fan.
  const std::vector<Triangle> tetrahedron = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  const std::vector<bool> keep = keep_largest_fans(4, tetrahedron);
  EXPECT_EQ(std::count(keep.begin(), keep.end(), true), 4);
}

TEST(KeepLargestFans, KeepsTheLargerFanAtAPinchedVertex) {
  // Vertex 0 carries a fan of two triangles (0,1,2), (0,2,3) and, touching it only at 0, a
  // lone triangle (0,4,5): the lone one goes.
  const std::vector<Triangle> bowtie = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}};
  const std::vector<bool> keep = keep_largest_fans(6, bowtie);
  EXPECT_TRUE(keep[0]);
  EXPECT_TRUE(keep[1]);
  EXPECT_FALSE(keep[2]);
}

TEST(KeepLargestFans, KeepsTheFanOfTheLowestTriangleBetweenEqualOnes) {
  const std::vector<Triangle> bowtie = {{0, 4, 5}, {0, 1, 2}};
  const std::vector<bool> keep = keep_largest_fans(6, bowtie);
  EXPECT_TRUE(keep[0]);
  EXPECT_FALSE(keep[1]);
}

}  // namespace
}  // namespace tessera
