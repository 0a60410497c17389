// SPDX-License-Identifier: MIT
// close_boundary_notches: a boundary vertex inside S marks uncovered M ∩ S next to it.
#include "tessera/methods/common/boundary_notches.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

constexpr int kCells = 4;
constexpr double kSide = 1.0 / kCells;

// The unit square of the plane z = 0 as a grid of kCells² squares, each cut along its diagonal.
TriangleMesh square_grid() {
  TriangleMesh mesh(3);
  for (int j = 0; j <= kCells; ++j) {
    for (int i = 0; i <= kCells; ++i) {
      mesh.add_vertex(Eigen::Vector3d(i * kSide, j * kSide, 0.0));
    }
  }
  const auto at = [](int i, int j) { return j * (kCells + 1) + i; };
  for (int j = 0; j < kCells; ++j) {
    for (int i = 0; i < kCells; ++i) {
      mesh.add_triangle(at(i, j), at(i + 1, j), at(i + 1, j + 1));
      mesh.add_triangle(at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
  return mesh;
}

Domain unit_square() {
  const double inf = std::numeric_limits<double>::infinity();
  return Domain::box(Eigen::Vector3d(0.0, 0.0, -inf), Eigen::Vector3d(1.0, 1.0, inf));
}

// Removes the triangles whose index is listed, and the vertices no triangle uses then.
void remove_triangles(TriangleMesh& mesh, const std::vector<int>& gone) {
  std::vector<bool> keep(mesh.triangle_count(), true);
  for (int t : gone) {
    keep[t] = false;
  }
  mesh.keep_triangles(keep);
}

TEST(BoundaryNotches, AMissingTriangleAtTheBoundaryIsPutBack) {
  const Plane plane;
  const Domain domain = unit_square();
  TriangleMesh mesh = square_grid();
  // Triangle 2 is (x, y) = (0.25, 0), (0.5, 0), (0.5, 0.25): without it the boundary runs from
  // (0.25, 0) in to (0.5, 0.25), inside S, and back out to (0.5, 0).
  remove_triangles(mesh, {2});
  ASSERT_NEAR(surface_area(mesh), 1.0 - 0.5 * kSide * kSide, 1e-12);
  const NotchClosing closing = close_boundary_notches(plane, domain, mesh, 2 * kSide);
  EXPECT_EQ(closing.added_triangles, 1);
  EXPECT_NEAR(surface_area(mesh), 1.0, 1e-12);
  const MeshValidation validation = validate(mesh, plane, domain);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 1);
  // Every boundary vertex on the square's sides again.
  const MeshTopology topology(mesh);
  for (int e : topology.boundary_edges()) {
    for (int v : topology.edge(e)) {
      EXPECT_LE(domain.boundary_distance(mesh.point(v)).signed_distance, 1e-12);
    }
  }
}

TEST(BoundaryNotches, ACompleteMeshIsLeftAlone) {
  const Plane plane;
  TriangleMesh mesh = square_grid();
  const std::vector<Triangle> before = mesh.triangles();
  EXPECT_EQ(close_boundary_notches(plane, unit_square(), mesh, 2 * kSide).added_triangles, 0);
  EXPECT_EQ(mesh.triangles(), before);
}

TEST(BoundaryNotches, AHoleWiderThanTheLongestEdgeAllowedStays) {
  const Plane plane;
  TriangleMesh mesh = square_grid();
  // The whole bottom row (8 triangles): its boundary vertices inside S are a quarter up, and
  // closing it would take edges across the whole square.
  remove_triangles(mesh, {0, 1, 2, 3, 4, 5, 6, 7});
  const double area = surface_area(mesh);
  const NotchClosing closing = close_boundary_notches(plane, unit_square(), mesh, 2 * kSide);
  // Ears along the row are allowed only up to edges of 2·kSide, and they must keep every
  // boundary vertex's triangles valid: whatever was added stays valid, and the row is not
  // covered over.
  const MeshValidation validation = validate(mesh, plane, unit_square());
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_LT(surface_area(mesh), 1.0 - 1e-6);
  EXPECT_GE(surface_area(mesh), area);
  EXPECT_EQ(mesh.triangle_count(), 24 + closing.added_triangles);
}

}  // namespace
}  // namespace tessera
