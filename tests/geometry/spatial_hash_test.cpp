// SPDX-License-Identifier: MIT
#include "tessera/geometry/spatial_hash.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <set>

#include "geometry/mesh_examples.h"
#include "tessera/core/error.h"

namespace tessera {
namespace {

// Random triangles in R^n whose sizes span three orders of magnitude (as atlas radii do),
// scattered in the unit cube.
TriangleMesh random_triangles(int n, int count, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::uniform_real_distribution<double> offset(-1.0, 1.0);
  Eigen::MatrixXd points(n, 3 * count);
  std::vector<Triangle> triangles;
  for (int t = 0; t < count; ++t) {
    Eigen::VectorXd center(n);
    for (int i = 0; i < n; ++i) {
      center(i) = unit(generator);
    }
    const double size = 0.001 * std::pow(1000.0, unit(generator));
    for (int k = 0; k < 3; ++k) {
      for (int i = 0; i < n; ++i) {
        points(i, 3 * t + k) = center(i) + size * offset(generator);
      }
    }
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return TriangleMesh(points, triangles);
}

// Brute force: a lower bound of the pairs that must be found (two vertices within the summed
// margins), and the property every reported pair has (overlapping enlarged boxes in R^n).
void expect_complete_and_sound(const TriangleMesh& mesh, const std::vector<double>& margins) {
  const auto pairs = nearby_triangle_pairs(mesh.points(), mesh.triangles(), margins);
  const std::set<std::pair<int, int>> found(pairs.begin(), pairs.end());
  EXPECT_EQ(found.size(), pairs.size()) << "each pair once";
  const int count = mesh.triangle_count();
  int required = 0;
  for (int s = 0; s < count; ++s) {
    for (int t = s + 1; t < count; ++t) {
      if (margins[s] < 0 || margins[t] < 0) {
        continue;
      }
      double closest = std::numeric_limits<double>::infinity();
      bool boxes_overlap = true;
      for (int a : mesh.triangle(s)) {
        for (int b : mesh.triangle(t)) {
          closest = std::min(closest, (mesh.point(a) - mesh.point(b)).norm());
        }
      }
      for (int i = 0; i < mesh.ambient_dimension(); ++i) {
        double s_lower = 1e300, s_upper = -1e300, t_lower = 1e300, t_upper = -1e300;
        for (int k = 0; k < 3; ++k) {
          s_lower = std::min(s_lower, mesh.point(mesh.triangle(s)[k])(i));
          s_upper = std::max(s_upper, mesh.point(mesh.triangle(s)[k])(i));
          t_lower = std::min(t_lower, mesh.point(mesh.triangle(t)[k])(i));
          t_upper = std::max(t_upper, mesh.point(mesh.triangle(t)[k])(i));
        }
        const double margin = margins[s] + margins[t];
        boxes_overlap = boxes_overlap && s_upper + margin >= t_lower && t_upper + margin >= s_lower;
      }
      const bool is_found = found.count({s, t}) == 1;
      if (closest <= margins[s] + margins[t]) {
        ++required;
        EXPECT_TRUE(is_found) << "pair " << s << ", " << t << " at distance " << closest;
      }
      if (is_found) {
        EXPECT_TRUE(boxes_overlap) << "pair " << s << ", " << t;
      }
    }
  }
  EXPECT_GT(required, 0) << "the test must exercise the search";
}

TEST(NearbyTrianglePairs, FindsEveryClosePairAmongTrianglesOfVeryDifferentSizesInR3) {
  const TriangleMesh mesh = random_triangles(3, 600, 1);
  std::vector<double> margins(mesh.triangle_count(), 0.01);
  expect_complete_and_sound(mesh, margins);
}

TEST(NearbyTrianglePairs, FindsEveryClosePairInR6ThroughItsThreeDimensionalView) {
  const TriangleMesh mesh = random_triangles(6, 600, 2);
  std::vector<double> margins(mesh.triangle_count(), 0.05);
  margins[3] = -1.0;  // left out
  margins[10] = 0.0;
  expect_complete_and_sound(mesh, margins);
  for (const auto& [s, t] : nearby_triangle_pairs(mesh.points(), mesh.triangles(), margins)) {
    EXPECT_TRUE(s != 3 && t != 3);
  }
}

TEST(NearbyTrianglePairs, FindsTheNeighboursOfEveryTriangleOfAMesh) {
  // In a closed mesh every triangle touches its edge neighbours (distance 0).
  const TriangleMesh mesh = examples::icosphere(3);
  const std::vector<double> margins(mesh.triangle_count(), 0.0);
  const auto pairs = nearby_triangle_pairs(mesh.points(), mesh.triangles(), margins);
  const std::set<std::pair<int, int>> found(pairs.begin(), pairs.end());
  for (int s = 0; s < mesh.triangle_count(); ++s) {
    for (int t = s + 1; t < mesh.triangle_count(); ++t) {
      int shared = 0;
      for (int v : mesh.triangle(s)) {
        shared += std::count(mesh.triangle(t).begin(), mesh.triangle(t).end(), v);
      }
      if (shared > 0) {
        EXPECT_EQ(found.count({s, t}), 1u) << s << ", " << t;
      }
    }
  }
  // A vertex has 5 or 6 triangles, so a triangle shares a vertex with at most 12 others; the
  // boxes of a curved mesh add a few more, but nothing like all N.
  EXPECT_LT(pairs.size(), 20u * mesh.triangle_count());
}

TEST(NearbyTrianglePairs, RejectsAMarginPerTriangleMismatch) {
  const TriangleMesh mesh = examples::octahedron();
  EXPECT_THROW(nearby_triangle_pairs(mesh.points(), mesh.triangles(), std::vector<double>(3, 0.0)),
               InvalidArgument);
}

}  // namespace
}  // namespace tessera
