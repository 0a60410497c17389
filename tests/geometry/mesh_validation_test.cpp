// SPDX-License-Identifier: MIT
// validate() without a problem: the combinatorial checks (topology, manifoldness, degenerate and
// duplicate triangles, indices, coordinates) and the counts they report.
#include "tessera/geometry/mesh_validation.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <string>

#include "geometry/mesh_examples.h"
#include "geometry/validation_expectations.h"
#include "support/front_run.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

TEST(MeshValidation, OctahedronIsAValidSphere) {
  const MeshValidation validation = validate(examples::octahedron());
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.vertex_count, 6);
  EXPECT_EQ(validation.referenced_vertex_count, 6);
  EXPECT_EQ(validation.edge_count, 12);
  EXPECT_EQ(validation.triangle_count, 8);
  EXPECT_EQ(validation.euler_characteristic, 2);
  EXPECT_TRUE(validation.is_closed());
  EXPECT_TRUE(validation.is_orientable);
  EXPECT_EQ(validation.genus, 0);
  EXPECT_EQ(validation.component_count, 1);
  EXPECT_EQ(validation.boundary_loop_count, 0);
  EXPECT_NE(validation.report().find("valid: no defects"), std::string::npos);
}

TEST(MeshValidation, SubdividedIcosahedronIsAValidSphere) {
  for (int s = 0; s <= 3; ++s) {
    const MeshValidation validation = validate(examples::icosphere(s));
    const int scale = 1 << (2 * s);  // 4^s
    EXPECT_TRUE(validation.is_valid()) << validation.report();
    EXPECT_EQ(validation.vertex_count, 10 * scale + 2);
    EXPECT_EQ(validation.edge_count, 30 * scale);
    EXPECT_EQ(validation.triangle_count, 20 * scale);
    EXPECT_EQ(validation.euler_characteristic, 2);
    EXPECT_EQ(validation.genus, 0);
  }
}

TEST(MeshValidation, TorusHasGenusOne) {
  const MeshValidation validation = validate(examples::torus(10, 7));
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, 0);
  EXPECT_TRUE(validation.is_closed());
  EXPECT_EQ(validation.genus, 1);
}

TEST(MeshValidation, GenusAddsOverComponents) {
  const MeshValidation validation = validate(examples::disjoint_union(
      examples::torus(6, 5),
      examples::disjoint_union(examples::torus(5, 4), examples::octahedron())));
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.component_count, 3);
  EXPECT_EQ(validation.euler_characteristic, 0 + 0 + 2);
  EXPECT_EQ(validation.genus, 2);
}

TEST(MeshValidation, SquareGridIsADiskWithOneBoundaryLoop) {
  const int k = 6;
  const MeshValidation validation = validate(examples::square_grid(k));
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.ambient_dimension, 2);
  EXPECT_EQ(validation.euler_characteristic, 1);
  EXPECT_FALSE(validation.is_closed());
  EXPECT_EQ(validation.genus, -1);  // genus is reported for closed surfaces only
  EXPECT_EQ(validation.boundary_edge_count, 4 * k);
  EXPECT_EQ(validation.boundary_loop_count, 1);
  EXPECT_EQ(validation.boundary_loop_vertex_counts, std::vector<int>{4 * k});
}

TEST(MeshValidation, MobiusStripIsValidAndNotOrientable) {
  const int m = 7;
  const MeshValidation validation = validate(examples::mobius_strip(m));
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_FALSE(validation.is_orientable);
  EXPECT_EQ(validation.non_orientable_component_count, 1);
  EXPECT_EQ(validation.inconsistent_orientation_count, 0);  // unavoidable, so not a defect
  EXPECT_EQ(validation.euler_characteristic, 0);
  EXPECT_EQ(validation.boundary_loop_vertex_counts, std::vector<int>{2 * m});
  EXPECT_EQ(validation.genus, -1);
  EXPECT_NE(validation.report().find("non-orientable"), std::string::npos);
}

TEST(MeshValidation, FlippedTriangleOnMobiusStripIsNotADefectButOnTorusIs) {
  TriangleMesh mobius = examples::mobius_strip(5);
  std::vector<Triangle> triangles = mobius.triangles();
  std::swap(triangles[4][1], triangles[4][2]);
  mobius.set_triangles(triangles);
  EXPECT_TRUE(validate(mobius).is_valid()) << validate(mobius).report();

  // The same flip in an orientable component next to the strip is reported.
  TriangleMesh both = examples::disjoint_union(examples::mobius_strip(5), examples::torus(4, 4));
  triangles = both.triangles();
  std::swap(triangles[12][1], triangles[12][2]);  // triangle 2 of the torus
  both.set_triangles(triangles);
  const MeshValidation validation = validate(both);
  EXPECT_EQ(validation.inconsistent_orientation_count, 3);
  EXPECT_EQ(validation.non_orientable_component_count, 1);
  expect_defect_named(validation, MeshDefectKind::InconsistentOrientation, "triangles ");
}

TEST(MeshValidation, DetectsBowTieVertex) {
  // Two triangles that share only vertex 0.
  Eigen::MatrixXd points(2, 5);
  points << 0, 1, 1, -1, -1,  //
      0, 0, 1, 0, -1;
  const MeshValidation validation = validate(TriangleMesh(points, {{0, 1, 2}, {0, 3, 4}}));
  expect_defect_kinds(validation, {MeshDefectKind::NonManifoldVertex});
  EXPECT_EQ(validation.non_manifold_vertex_count, 1);
  expect_defect_named(
      validation, MeshDefectKind::NonManifoldVertex,
      "vertex 0 near (0, 0) is shared by 2 fans of triangles that share no edge there: {0}, {1}");
  EXPECT_FALSE(validation.is_manifold());
}

TEST(MeshValidation, DetectsDoubleConeApex) {
  // Two octahedron caps (four triangles around +z each) glued at the apex only: each link is
  // a cycle, but the vertex has two of them.
  const TriangleMesh octahedron = examples::octahedron();
  std::vector<Triangle> caps;
  for (const Triangle& t : octahedron.triangles()) {
    if (t[0] == 4 || t[1] == 4 || t[2] == 4) {
      caps.push_back(t);
    }
  }
  TriangleMesh mesh = examples::disjoint_union(TriangleMesh(octahedron.points(), caps),
                                               TriangleMesh(octahedron.points(), caps));
  std::vector<Triangle> glued = mesh.triangles();
  for (Triangle& t : glued) {
    for (int& v : t) {
      v = v == 4 + 6 ? 4 : v;  // the second apex becomes the first
    }
  }
  glued.push_back({5, 0, 2});  // refer to the otherwise unused vertices 5 and 11
  glued.push_back({11, 6, 8});
  mesh.set_triangles(glued);
  const MeshValidation validation = validate(mesh);
  EXPECT_EQ(validation.non_manifold_vertex_count, 1) << validation.report();
  expect_defect_named(validation, MeshDefectKind::NonManifoldVertex,
                      "vertex 4 near (0, 0, 1) is shared by 2 fans");
}

TEST(MeshValidation, DetectsThreeTrianglesOnAnEdge) {
  Eigen::MatrixXd points(3, 5);
  points << 0, 1, 0, 0, 0.5,  //
      0, 0, 1, -1, 0.5,       //
      0, 0, 0, 0, 1;
  const MeshValidation validation =
      validate(TriangleMesh(points, {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}}));
  expect_defect_kinds(validation, {MeshDefectKind::NonManifoldEdge});
  EXPECT_EQ(validation.non_manifold_edge_count, 1);
  expect_defect_named(validation, MeshDefectKind::NonManifoldEdge,
                      "edge (0, 1) near (0.5, 0, 0) has 3 triangles: 0, 1, 2");
}

TEST(MeshValidation, DetectsFlippedTriangle) {
  TriangleMesh mesh = examples::octahedron();
  std::vector<Triangle> triangles = mesh.triangles();
  std::swap(triangles[5][1], triangles[5][2]);
  mesh.set_triangles(triangles);
  const MeshValidation validation = validate(mesh);
  expect_defect_kinds(validation, {MeshDefectKind::InconsistentOrientation});
  EXPECT_EQ(validation.inconsistent_orientation_count, 3);  // the three edges of triangle 5
  EXPECT_TRUE(validation.is_orientable);
  EXPECT_EQ(validation.genus, 0);  // the surface is still a sphere
  expect_defect_named(validation, MeshDefectKind::InconsistentOrientation, " and 5 both traverse");

  mesh.set_triangles(orient_consistently(mesh));
  EXPECT_TRUE(validate(mesh).is_valid()) << validate(mesh).report();
}

TEST(MeshValidation, DetectsDuplicateTriangle) {
  TriangleMesh mesh = examples::octahedron();
  const Triangle t = mesh.triangle(2);
  mesh.add_triangle(t[1], t[0], t[2]);  // same vertex set, other orientation
  const MeshValidation validation = validate(mesh);
  EXPECT_EQ(validation.duplicate_triangle_count, 1);
  std::ostringstream expected;
  expected << "triangle 8 = (" << t[1] << ", " << t[0] << ", " << t[2]
           << ") near (0.3333, -0.3333, 0.3333) repeats triangle 2";
  expect_defect_named(validation, MeshDefectKind::DuplicateTriangle, expected.str());
  EXPECT_EQ(validation.non_manifold_edge_count, 3);  // a duplicate also overloads its edges
}

TEST(MeshValidation, DetectsIndexOutOfRangeAndStillReportsTheRest) {
  TriangleMesh mesh = examples::octahedron();
  mesh.add_triangle(0, 2, 17);
  mesh.add_triangle(-1, 2, 4);
  const MeshValidation validation = validate(mesh);
  EXPECT_EQ(validation.index_out_of_range_count, 2);
  expect_defect_named(validation, MeshDefectKind::IndexOutOfRange,
                      "triangle 8 = (0, 2, 17) near (0.5, 0.5, 0) has index 17 outside [0, 6)");
  expect_defect_named(validation, MeshDefectKind::IndexOutOfRange,
                      "triangle 9 = (-1, 2, 4) near (0, 0.5, 0.5) has index -1 outside [0, 6)");
  EXPECT_EQ(validation.triangle_count, 10);
  EXPECT_EQ(validation.euler_characteristic, 2);  // of the 8 well-formed triangles
  EXPECT_EQ(validation.genus, -1);
}

TEST(MeshValidation, DetectsRepeatedIndex) {
  TriangleMesh mesh = examples::octahedron();
  mesh.add_triangle(3, 1, 3);
  const MeshValidation validation = validate(mesh);
  expect_defect_kinds(validation, {MeshDefectKind::RepeatedIndex});
  expect_defect_named(validation, MeshDefectKind::RepeatedIndex,
                      "triangle 8 = (3, 1, 3) near (-0.3333, -0.6667, 0) repeats vertex 3");
}

TEST(MeshValidation, DetectsCollinearTriangleInR5ButNotAThinOne) {
  // p2 = p0 + 0.3 (p1 - p0) is collinear up to rounding of its coordinates.
  Eigen::MatrixXd points(5, 4);
  points.col(0) << 0.1, -0.7, 2.3, 0.4, 1.9;
  points.col(1) << 1.3, 0.2, -0.6, 2.2, 0.5;
  points.col(2) = points.col(0) + 0.3 * (points.col(1) - points.col(0));
  // p3: an honest sliver, apex 1e-7 * |p1 - p0| off the line.
  Eigen::VectorXd normal(5);
  normal << 0, 0, 0, 0, 1;
  const Eigen::VectorXd along = points.col(1) - points.col(0);
  normal -= normal.dot(along) / along.squaredNorm() * along;
  points.col(3) = points.col(0) + 0.6 * along + 1e-7 * along.norm() * normal.normalized();
  const MeshValidation validation = validate(TriangleMesh(points, {{0, 1, 2}, {1, 0, 3}}));
  EXPECT_EQ(validation.degenerate_triangle_count, 1) << validation.report();
  expect_defect_named(validation, MeshDefectKind::DegenerateTriangle, "triangle 0 = (0, 1, 2)");
}

TEST(MeshValidation, DetectsCoincidentVertices) {
  Eigen::MatrixXd points(3, 3);
  points << 1, 1, 1,  //
      2, 2, 2,        //
      3, 3, 3;
  const MeshValidation validation = validate(TriangleMesh(points, {{0, 1, 2}}));
  EXPECT_EQ(validation.degenerate_triangle_count, 1) << validation.report();
}

TEST(MeshValidation, DetectsUnreferencedVertex) {
  TriangleMesh mesh = examples::octahedron();
  mesh.add_vertex(Eigen::Vector3d(5, 5, 5));
  const MeshValidation validation = validate(mesh);
  expect_defect_kinds(validation, {MeshDefectKind::UnreferencedVertex});
  EXPECT_EQ(validation.vertex_count, 7);
  EXPECT_EQ(validation.referenced_vertex_count, 6);
  EXPECT_EQ(validation.euler_characteristic, 2);  // V counts referenced vertices only
  expect_defect_named(validation, MeshDefectKind::UnreferencedVertex,
                      "vertex 6 at (5, 5, 5) is in no triangle");
}

TEST(MeshValidation, DetectsNaNCoordinate) {
  TriangleMesh mesh = examples::octahedron();
  mesh.mutable_point(2)(1) = std::numeric_limits<double>::quiet_NaN();
  const MeshValidation validation = validate(mesh);
  // Only the NaN: the triangles at vertex 2 are not also called degenerate.
  expect_defect_kinds(validation, {MeshDefectKind::NonFiniteCoordinate});
  EXPECT_EQ(validation.non_finite_vertex_count, 1);
  expect_defect_named(validation, MeshDefectKind::NonFiniteCoordinate, "vertex 2 = (0, nan, 0)");
}

TEST(MeshValidation, CountsAreCompleteButExamplesAreCapped) {
  TriangleMesh mesh = examples::octahedron();
  for (int i = 0; i < 20; ++i) {
    mesh.add_vertex(Eigen::Vector3d(i, 0, 0));
  }
  const MeshValidation validation = validate(mesh, {.max_examples = 3});
  ASSERT_EQ(validation.defects.size(), 1u);
  EXPECT_EQ(validation.defects[0].count, 20);
  EXPECT_EQ(validation.defects[0].examples.size(), 3u);
  EXPECT_EQ(validation.count(MeshDefectKind::UnreferencedVertex), 20);
  EXPECT_NE(validation.report().find("... and 17 more"), std::string::npos) << validation.report();
}

TEST(MeshValidation, RejectsNegativeOptionsNamingTheField) {
  try {
    validate(examples::octahedron(), {.degenerate_area_ratio = -1});
    FAIL() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(
        std::string(e.what()).find("ValidationOptions::degenerate_area_ratio = -1 must be >= 0"),
        std::string::npos)
        << e.what();
  }
}

// Counts on a large mesh (timing belongs in bench/, see bench/RESULTS.md).
TEST(MeshValidation, CountsAMillionTriangleTorus) {
  const TriangleMesh mesh = examples::torus(1000, 500);
  const MeshValidation validation = validate(mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.triangle_count, 1'000'000);
  EXPECT_EQ(validation.edge_count, 1'500'000);
  EXPECT_EQ(validation.genus, 1);
}

}  // namespace
}  // namespace tessera

// validate_around judges coordinates and shapes only at the vertices it is told changed, and the
// whole topology: a degenerate triangle elsewhere is not judged again, one at a changed vertex
// is, and a topological defect anywhere is.
TEST(MeshValidation, AroundChangedVerticesJudgesTheirShapesAndAllTopology) {
  using tessera::TriangleMesh;
  TriangleMesh mesh = tessera::examples::square_grid(4);
  ASSERT_TRUE(tessera::validate(mesh).is_valid());
  const std::vector<tessera::Triangle>& triangles = mesh.triangles();
  // Flatten the first triangle: its third corner onto the midpoint of the other two.
  const tessera::Triangle flat = triangles.front();
  mesh.mutable_point(flat[2]) = 0.5 * (mesh.point(flat[0]) + mesh.point(flat[1]));
  const int degenerate = tessera::validate(mesh).degenerate_triangle_count;
  EXPECT_GE(degenerate, 1);
  // Far from it (a vertex of no triangle that touches flat[2]'s triangles): not judged.
  int far = -1;
  for (int v = 0; v < mesh.vertex_count() && far < 0; ++v) {
    bool touches = false;
    for (const tessera::Triangle& t : triangles) {
      const bool has_v = t[0] == v || t[1] == v || t[2] == v;
      const bool has_moved = t[0] == flat[2] || t[1] == flat[2] || t[2] == flat[2];
      touches = touches || (has_v && has_moved);
    }
    far = touches ? -1 : v;
  }
  ASSERT_GE(far, 0);
  const std::array<int, 1> elsewhere{far};
  EXPECT_TRUE(tessera::validate_around(mesh, elsewhere).is_valid());
  const std::array<int, 1> moved{flat[2]};
  const tessera::MeshValidation around = tessera::validate_around(mesh, moved);
  EXPECT_EQ(around.degenerate_triangle_count, degenerate);
  // A triangle repeated far from the changed vertex is still a topological defect.
  std::vector<tessera::Triangle> doubled = triangles;
  doubled.push_back(triangles.back());
  mesh.set_triangles(std::move(doubled));
  EXPECT_EQ(tessera::validate_around(mesh, elsewhere).duplicate_triangle_count, 1);
  const std::array<int, 1> outside{mesh.vertex_count()};
  EXPECT_THROW(tessera::validate_around(mesh, outside), tessera::InvalidArgument);
}
