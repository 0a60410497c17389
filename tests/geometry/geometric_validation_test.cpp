// SPDX-License-Identifier: MIT
// validate() with a problem and a domain: orientation along M, overlaps on M, vertices in S
// (docs/validation.md), on planted defects and on meshes the methods make.
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
#include "support/sparse_view.h"
#include "tessera/core/describe.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/methods/atlas/atlas.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

// --- Geometric validity: orientation along M, overlaps on M, vertices in S ------------------

// Options that keep every example, so that a test can look for the one it planted.
ValidationOptions all_examples() {
  ValidationOptions options;
  options.max_examples = 100000;
  return options;
}

bool contains(const std::vector<int>& list, int value) {
  return std::find(list.begin(), list.end(), value) != list.end();
}

Eigen::VectorXd centroid_of(const TriangleMesh& mesh, int t) {
  const Triangle& tri = mesh.triangle(t);
  return (mesh.point(tri[0]) + mesh.point(tri[1]) + mesh.point(tri[2])) / 3.0;
}

// No geometric defect (the combinatorial ones are the method tests' business, but a good mesh
// has none either).
void expect_geometrically_valid(const MeshValidation& validation) {
  EXPECT_TRUE(validation.is_geometry_checked);
  EXPECT_EQ(validation.flipped_triangle_count, 0) << validation.report();
  EXPECT_EQ(validation.overlapping_pair_count, 0) << validation.report();
  EXPECT_EQ(validation.vertex_outside_domain_count, 0) << validation.report();
  EXPECT_TRUE(validation.flipped_triangles.empty());
  EXPECT_TRUE(validation.overlapping_triangle_pairs.empty());
  EXPECT_TRUE(validation.vertices_outside_domain.empty());
  EXPECT_TRUE(validation.is_valid()) << validation.report();
}

TEST(GeometricValidation, OnlyTheOverloadWithAProblemChecksGeometry) {
  const TriangleMesh mesh = examples::icosphere(2);
  EXPECT_FALSE(validate(mesh).is_geometry_checked);
  EXPECT_NE(validate(mesh).report().find("geometry: not checked"), std::string::npos);
  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain());
  expect_geometrically_valid(validation);
  EXPECT_EQ(validation.unoriented_triangle_count, 0);
}

// The octahedron is as coarse as a mesh of the sphere gets (triangles at 55° to the sphere at
// their corners); projected onto one face's plane, the faces that share a vertex with it
// overlap it, but they cover other parts of M: no overlap. (No flip either, though the
// orientation transport is at its limit here: see docs/validation.md.)
TEST(GeometricValidation, OctahedronAndIcospheresAreValidMeshesOfTheSphere) {
  expect_geometrically_valid(validate(examples::octahedron(), Sphere(1.0), Domain()));
  for (int subdivisions : {0, 1, 3}) {
    expect_geometrically_valid(validate(examples::icosphere(subdivisions), Sphere(1.0), Domain()));
  }
}

// (a) One vertex moved across the opposite edge of one of its triangles, then back onto M: the
// combinatorics are unchanged, the triangle is reversed along M.
TEST(GeometricValidation, FindsATriangleFlippedByMovingAVertexAcrossItsOppositeEdge) {
  TriangleMesh mesh = examples::icosphere(3);
  const int t = 100;
  const Triangle tri = mesh.triangle(t);
  const Eigen::VectorXd moved =
      (mesh.point(tri[1]) + mesh.point(tri[2]) - mesh.point(tri[0])).normalized();
  mesh.mutable_point(tri[0]) = moved;
  ASSERT_TRUE(validate(mesh).is_valid()) << "the combinatorics must stay valid";

  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain(), all_examples());
  EXPECT_FALSE(validation.is_valid());
  EXPECT_TRUE(contains(validation.flipped_triangles, t)) << validation.report();
  EXPECT_EQ(validation.count(MeshDefectKind::FlippedTriangle),
            static_cast<int>(validation.flipped_triangles.size()));
  // Only triangles of the moved vertex's fan, and the triangle across t's far edge (which t
  // now folds over: of a pair folded against each other once, either may be the flipped one,
  // so both are reported), can be affected.
  const MeshTopology topology(mesh);
  std::vector<int> near(topology.vertex_triangles(tri[0]).begin(),
                        topology.vertex_triangles(tri[0]).end());
  for (int s : topology.edge_triangles(topology.find_edge(tri[1], tri[2]))) {
    near.push_back(s);
  }
  for (int flipped : validation.flipped_triangles) {
    EXPECT_TRUE(contains(near, flipped)) << "triangle " << flipped << " is not at the moved vertex";
  }
  std::ostringstream name;
  name << "triangle " << t << " (vertices " << tri[0] << ", " << tri[1] << ", " << tri[2]
       << ") near " << describe_point(centroid_of(mesh, t)) << ": folded over its neighbour";
  expect_defect_named(validation, MeshDefectKind::FlippedTriangle, name.str());
}

// The same in R^4: the flat torus, whose tangent bases are propagated over the whole mesh.
TEST(GeometricValidation, FindsAFlippedTriangleInR4) {
  auto run = testing::run_front("flat_torus");
  ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
  TriangleMesh& mesh = run.result.mesh;
  expect_geometrically_valid(validate(mesh, *run.setup.problem, run.setup.domain));
  const int t = mesh.triangle_count() / 2;
  const Triangle tri = mesh.triangle(t);
  Eigen::VectorXd moved = mesh.point(tri[1]) + mesh.point(tri[2]) - mesh.point(tri[0]);
  moved.head(2).normalize();  // back onto x1² + x2² = 1, x3² + x4² = 1
  moved.tail(2).normalize();
  mesh.mutable_point(tri[0]) = moved;
  const MeshValidation validation =
      validate(mesh, *run.setup.problem, run.setup.domain, all_examples());
  EXPECT_TRUE(contains(validation.flipped_triangles, t)) << validation.report();
  expect_defect_named(validation, MeshDefectKind::FlippedTriangle,
                      "near " + describe_point(centroid_of(mesh, t)) + ": folded over its neighbour");
}

// The same through the sparse linearisation (bordered LU, oriented by the BFS parent's basis).
TEST(GeometricValidation, FindsAFlippedTriangleWithASparseJacobian) {
  const Sphere sphere(1.0);
  const testing::SparseView sparse_sphere(sphere);
  TriangleMesh mesh = examples::icosphere(3);
  expect_geometrically_valid(validate(mesh, sparse_sphere, Domain()));
  const int t = 300;
  const Triangle tri = mesh.triangle(t);
  mesh.mutable_point(tri[0]) =
      (mesh.point(tri[1]) + mesh.point(tri[2]) - mesh.point(tri[0])).normalized();
  const MeshValidation validation = validate(mesh, sparse_sphere, Domain(), all_examples());
  EXPECT_TRUE(contains(validation.flipped_triangles, t)) << validation.report();
  EXPECT_EQ(validation.flipped_triangles, validate(mesh, Sphere(1.0), Domain()).flipped_triangles)
      << "dense and sparse linearisations agree";
}

// A pair folded across its edge where one of them nearly stands across M at one end of the
// edge: the oriented cosines at the edge's ends are (0.979, 0.044) and (0.968, −0.259). The
// near-standing corner used to outvote the fold at the other end, and the pair, which covers
// the same part of M (the stress campaign's sampled check, seed 2026, case 65), passed as
// valid. Four vertices of that bezier partial mesh of cstr (n = 4), on M to 1e-13.
TEST(GeometricValidation, FindsAFoldOutvotedByACornerStandingAcrossM) {
  const ProblemSetup cstr = make_catalogue_problem("cstr");
  Eigen::MatrixXd points(4, 4);
  points.col(0) << 0.9898829515004597, 7.758186612266293, 0.041801549196827284, 11.756218147569577;
  points.col(1) << 0.9778258636122821, 7.742439161059287, 0.019138865996011563, 11.87702143476322;
  points.col(2) << 0.9877624796227416, 7.737124701873143, 0.035218311757177496, 11.74947144908997;
  points.col(3) << 0.9977910561834582, 7.729197500583389, 0.19865848209147535, 11.61946299180236;
  const TriangleMesh mesh(points, {{0, 1, 2}, {1, 0, 3}});
  const MeshValidation validation = validate(mesh, *cstr.problem, Domain(), all_examples());
  EXPECT_FALSE(validation.flipped_triangles.empty()) << validation.report();
  expect_defect_named(validation, MeshDefectKind::FlippedTriangle, "folded over its neighbour");
}

// The fan of vertex 5 (171 there) from a partial bezier mesh of the trough (stress seed 2026,
// case 512): its seven triangles turn 378° around the vertex in M's tangent plane. Two of them
// stand 68° from that plane and overlap the first by 3° and 15° at the vertex, a sliver 2.5 %
// of their area that the planar overlap test cannot prove (its chart's distortion bound is
// wider); the arcs of their corners at the vertex prove it.
TEST(GeometricValidation, FindsAFanThatTurnsMoreThanOnceAroundItsVertex) {
  const ProblemSetup trough = make_catalogue_problem("trough");
  Eigen::MatrixXd points(3, 9);
  points.col(0) << -0.07125026688062631, -0.01925652391371572, 0.06856330576524607;
  points.col(1) << -0.08977654877388115, -0.14, 0.09354380877312424;
  points.col(2) << -0.05157302235952197, -0.010207780063192295, 0.03605767054931434;
  points.col(3) << -0.07038504428618023, -0.03544023874183734, 0.010313828222482738;
  points.col(4) << -0.06667468077509026, -0.052079629342192346, 0.011597423930994664;
  points.col(5) << -0.05710125776843062, -0.053826896824526876, 0.016776425974450077;
  points.col(6) << -0.06326082761875645, -0.06630964554493496, 0.013047473882422634;
  points.col(7) << -0.05235911519469013, -0.07614236053331162, 0.022195310540544043;
  points.col(8) << -0.057033431439461, -0.08425371041751613, 0.0478819279305067;
  const std::vector<Triangle> fan = {{1, 5, 0}, {5, 2, 0}, {2, 5, 3}, {3, 5, 4},
                                     {4, 5, 6}, {6, 5, 7}, {8, 7, 5}};
  const MeshValidation validation =
      validate(TriangleMesh(points, fan), *trough.problem, Domain(), all_examples());
  EXPECT_EQ(validation.flipped_triangle_count, 0) << validation.report();
  const auto& pairs = validation.overlapping_triangle_pairs;
  EXPECT_NE(std::find(pairs.begin(), pairs.end(), std::pair<int, int>(0, 6)), pairs.end())
      << validation.report();
  expect_defect_named(validation, MeshDefectKind::OverlappingTriangles,
                      "both cover M next to vertex 5");

  // Without the first triangle (and its vertex 1) the fan covers the vertex's neighbourhood
  // once: valid.
  Eigen::MatrixXd open_points(3, 8);
  open_points << points.col(0), points.rightCols(7);
  std::vector<Triangle> open_fan;
  for (std::size_t t = 1; t < fan.size(); ++t) {
    Triangle tri = fan[t];
    for (int& v : tri) {
      v -= v > 1 ? 1 : 0;
    }
    open_fan.push_back(tri);
  }
  const MeshValidation once =
      validate(TriangleMesh(open_points, open_fan), *trough.problem, Domain(), all_examples());
  EXPECT_TRUE(once.is_valid()) << once.report();
}

// A triangle folded up to stand across M: neither orientation, flagged as standing across.
TEST(GeometricValidation, FindsATriangleStandingAcrossM) {
  TriangleMesh mesh = examples::icosphere(3);
  const int t = 200;
  const Triangle tri = mesh.triangle(t);
  // Move tri[0] radially outward so far that the triangle's plane contains the normal nearly.
  const Eigen::VectorXd midpoint = 0.5 * (mesh.point(tri[1]) + mesh.point(tri[2]));
  mesh.mutable_point(tri[0]) = midpoint + 0.5 * midpoint.normalized();
  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain(), all_examples());
  EXPECT_TRUE(contains(validation.flipped_triangles, t)) << validation.report();
  expect_defect_named(validation, MeshDefectKind::FlippedTriangle, "stands across M");
}

// A copy of a patch of triangles rotated slightly about an axis (so it stays on the sphere),
// added with new vertices: combinatorially disjoint from the original, geometrically on top.
TEST(GeometricValidation, FindsADoubledPatch) {
  const TriangleMesh sphere = examples::icosphere(3);
  const MeshTopology topology(sphere);
  const int center = 7;
  std::vector<int> patch(topology.vertex_triangles(center).begin(),
                         topology.vertex_triangles(center).end());
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.01, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  TriangleMesh mesh = sphere;
  std::map<int, int> copy_of;
  for (int t : patch) {
    for (int v : sphere.triangle(t)) {
      if (copy_of.count(v) == 0) {
        copy_of[v] = mesh.add_vertex(rotation * Eigen::Vector3d(sphere.point(v)));
      }
    }
  }
  for (int t : patch) {
    const Triangle& tri = sphere.triangle(t);
    mesh.add_triangle(copy_of[tri[0]], copy_of[tri[1]], copy_of[tri[2]]);
  }
  ASSERT_TRUE(validate(mesh).is_valid()) << "the copy is a disjoint, valid component";

  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain(), all_examples());
  EXPECT_EQ(validation.flipped_triangle_count, 0) << validation.report();
  EXPECT_GE(validation.overlapping_pair_count, static_cast<int>(patch.size()))
      << validation.report();
  EXPECT_EQ(validation.count(MeshDefectKind::OverlappingTriangles),
            static_cast<int>(validation.overlapping_triangle_pairs.size()));
  for (const auto& [s, t] : validation.overlapping_triangle_pairs) {
    EXPECT_LT(s, sphere.triangle_count()) << "an original triangle";
    EXPECT_GE(t, sphere.triangle_count()) << "and a copied one";
  }
  expect_defect_named(validation, MeshDefectKind::OverlappingTriangles, "both cover M near (");
}

// The same on a coarse mesh, where the chart's distortion bound (chord error 0.42 times a reach
// of 0.8) exceeds the overlap's width: a face of the octahedron, copied with corners moved 0.003
// along the sphere (the stress campaign's sphere_box front case 664 of seed 2034, two triangles of
// edge 1 on top of each other). Judged without the chart: the point of M over the overlap is the
// projection of a point inside each triangle.
TEST(GeometricValidation, FindsACoarseTriangleCoveredTwice) {
  const TriangleMesh octahedron = examples::octahedron();
  ASSERT_TRUE(validate(octahedron, Sphere(1.0), Domain()).is_valid());
  TriangleMesh mesh = octahedron;
  const Eigen::Matrix3d rotation =
      Eigen::AngleAxisd(0.003, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  const Triangle face = octahedron.triangle(0);
  std::array<int, 3> copy{};
  for (int k = 0; k < 3; ++k) {
    copy[k] = mesh.add_vertex(rotation * Eigen::Vector3d(octahedron.point(face[k])));
  }
  mesh.add_triangle(copy[0], copy[1], copy[2]);
  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain(), all_examples());
  EXPECT_EQ(validation.overlapping_pair_count, 1) << validation.report();
  ASSERT_EQ(validation.overlapping_triangle_pairs.size(), 1u);
  EXPECT_EQ(validation.overlapping_triangle_pairs[0],
            std::make_pair(0, octahedron.triangle_count()));
}

// Sheets that cross: the `crossing` problem's sphere and plane z = 0, each a component of its
// own, pass through each other along the circle, as M does. Valid, and the pairs of triangles
// where they cross are counted; the same plane doubled (two components on one sheet) is still
// an overlap.
TEST(GeometricValidation, ComponentsOnCrossingSheetsAreNotAnOverlap) {
  const ProblemSetup crossing = make_catalogue_problem("crossing");
  const TriangleMesh sphere = examples::icosphere(3);
  const TriangleMesh square = examples::square_grid(12);  // [0, 1]², mapped onto [−1.5, 1.5]²
  const auto plane_point = [&](int v) {
    return Eigen::Vector3d(3.0 * square.point(v).x() - 1.5, 3.0 * square.point(v).y() - 1.5, 0.0);
  };
  TriangleMesh mesh = sphere;
  const int offset = mesh.vertex_count();
  for (int v = 0; v < square.vertex_count(); ++v) {
    mesh.add_vertex(plane_point(v));
  }
  for (const Triangle& tri : square.triangles()) {
    mesh.add_triangle(offset + tri[0], offset + tri[1], offset + tri[2]);
  }
  const MeshValidation validation = validate(mesh, *crossing.problem, Domain(), all_examples());
  expect_geometrically_valid(validation);
  EXPECT_EQ(validation.component_count, 2);
  EXPECT_GT(validation.crossing_pair_count, 0) << validation.report();
  EXPECT_NE(validation.report().find("components cross"), std::string::npos)
      << validation.report();

  // The plane's grid once more, turned by 1° about the z-axis: it covers the plane again.
  const Eigen::Matrix3d turn = Eigen::AngleAxisd(std::numbers::pi / 180.0,
                                                 Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const int second = mesh.vertex_count();
  for (int v = 0; v < square.vertex_count(); ++v) {
    mesh.add_vertex(turn * plane_point(v));
  }
  for (const Triangle& tri : square.triangles()) {
    mesh.add_triangle(second + tri[0], second + tri[1], second + tri[2]);
  }
  const MeshValidation doubled = validate(mesh, *crossing.problem, Domain(), all_examples());
  EXPECT_GT(doubled.overlapping_pair_count, 0) << doubled.report();
  for (const auto& [s, t] : doubled.overlapping_triangle_pairs) {
    EXPECT_GE(s, sphere.triangle_count()) << "only the plane's copies overlap, not the sphere";
  }
}

// A fan that winds twice around its vertex: every triangle is oriented along M, yet the fan
// covers M twice. Triangles sharing only that vertex overlap; the arcs of their corners there
// prove it (check_fan_arcs).
TEST(GeometricValidation, FindsAFanWindingTwiceAroundItsVertex) {
  const int k = 9;  // triangles; each spans 80°, so the fan turns 720° (no vertex repeats)
  Eigen::MatrixXd points(3, k + 1);
  points.col(0) << 0, 0, 1;
  for (int i = 0; i < k; ++i) {
    const double angle = 4 * std::numbers::pi * i / k;
    points.col(i + 1) =
        Eigen::Vector3d(0.2 * std::cos(angle), 0.2 * std::sin(angle), 1.0).normalized();
  }
  std::vector<Triangle> triangles;
  for (int i = 0; i < k; ++i) {
    triangles.push_back({0, 1 + i, 1 + (i + 1) % k});
  }
  const TriangleMesh mesh(points, triangles);
  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain(), all_examples());
  EXPECT_EQ(validation.flipped_triangle_count, 0) << validation.report();
  EXPECT_GT(validation.overlapping_pair_count, 0) << validation.report();
  expect_defect_named(validation, MeshDefectKind::OverlappingTriangles,
                      "both cover M next to vertex 0");
}

// (c) The octahedron's vertices lie on the faces of the box [-1, 1]³; one moved 1e-6 outside.
TEST(GeometricValidation, FindsAVertexOneMillionthOutsideABox) {
  const Domain box = Domain::box(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1));
  TriangleMesh mesh = examples::octahedron();
  expect_geometrically_valid(validate(mesh, Sphere(1.0), box));
  mesh.mutable_point(4)(2) = 1.0 + 1e-6;  // vertex 4 is +e_z
  const MeshValidation validation = validate(mesh, Sphere(1.0), box);
  EXPECT_EQ(validation.vertex_outside_domain_count, 1);
  EXPECT_EQ(validation.vertices_outside_domain, std::vector<int>{4});
  expect_defect_named(validation, MeshDefectKind::VertexOutsideDomain,
                      "vertex 4 at (0, 0, 1) is 1e-06 outside the domain (");
}

// A stop request (ValidationOptions::stop_requested; a stopped `tessera mesh` after its grace)
// cuts the checks on M short and says what they left; the combinatorial checks and the domain
// check, which need no factorisation, still run in full, and nothing left is called unoriented.
TEST(GeometricValidation, AStopRequestCutsTheChecksOnMShortButNotTheDomainCheck) {
  const Domain box = Domain::box(Eigen::Vector3d::Constant(-1), Eigen::Vector3d::Constant(1));
  TriangleMesh mesh = examples::octahedron();
  mesh.mutable_point(4)(2) = 1.0 + 1e-6;  // vertex 4 is +e_z
  ValidationOptions options;
  int polls = 0;
  options.stop_requested = [&polls] {
    ++polls;
    return false;
  };
  const MeshValidation whole = validate(mesh, Sphere(1.0), box, options);
  EXPECT_GT(polls, 0);
  EXPECT_FALSE(whole.is_cut_short());
  EXPECT_EQ(whole.vertex_outside_domain_count, 1);

  options.stop_requested = [] { return true; };
  const MeshValidation cut = validate(mesh, Sphere(1.0), box, options);
  ASSERT_TRUE(cut.is_cut_short());
  EXPECT_EQ(cut.checks_cut_short.front(), "orientation along M: 6 of 6 vertices not judged");
  EXPECT_NE(cut.checks_cut_short.back().find("overlaps on M: "), std::string::npos)
      << cut.checks_cut_short.back();
  EXPECT_EQ(cut.unoriented_triangle_count, 0);
  EXPECT_EQ(cut.vertex_outside_domain_count, 1);  // the domain check is complete
  EXPECT_EQ(cut.triangle_count, whole.triangle_count);
  EXPECT_EQ(cut.euler_characteristic, 2);
  EXPECT_NE(cut.report().find("geometry: cut short by a stop request"), std::string::npos)
      << cut.report();

  // Valid as far as checked, and said so.
  mesh.mutable_point(4)(2) = 1.0;
  const MeshValidation valid = validate(mesh, Sphere(1.0), box, options);
  EXPECT_TRUE(valid.is_valid());
  EXPECT_NE(valid.report().find("valid as far as checked"), std::string::npos) << valid.report();
}

// The case: an atlas corner vertex 3.9e-7 outside its box must be reported; a vertex
// within rounding of a face must not.
TEST(GeometricValidation, FindsABoundaryVertexOfAClippedSphereMovedOutside) {
  auto setup = make_catalogue_problem("sphere");
  setup.domain = Domain::box(Eigen::Vector3d::Constant(-0.7), Eigen::Vector3d::Constant(0.7));
  setup.start = Eigen::Vector3d(0.5, 0.5, 0.5);
  FrontOptions options;
  options.step = 0.1;
  auto result = triangulate_by_front(*setup.problem, setup.start, setup.domain, options);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  TriangleMesh& mesh = result.mesh;
  expect_geometrically_valid(validate(mesh, *setup.problem, setup.domain));
  int on_face = -1;
  for (int v = 0; v < mesh.vertex_count() && on_face < 0; ++v) {
    if (std::abs(mesh.point(v)(0) - 0.7) < 1e-12) {
      on_face = v;
    }
  }
  ASSERT_GE(on_face, 0) << "the sphere of radius 1 crosses the face x = 0.7";
  mesh.mutable_point(on_face)(0) = 0.7 * (1 + 4 * std::numeric_limits<double>::epsilon());
  EXPECT_EQ(validate(mesh, *setup.problem, setup.domain).vertex_outside_domain_count, 0)
      << "a few ulp outside is rounding";
  mesh.mutable_point(on_face)(0) = 0.7 + 3.9e-7;
  const MeshValidation validation = validate(mesh, *setup.problem, setup.domain);
  EXPECT_EQ(validation.vertices_outside_domain, std::vector<int>{on_face}) << validation.report();
  expect_defect_named(validation, MeshDefectKind::VertexOutsideDomain, "3.9e-07 outside");
}

// (d) Good meshes of several surfaces: no geometric defect (no false positives).
TEST(GeometricValidation, FrontMeshesOfSphereTorusAndFlatTorusAreGeometricallyValid) {
  for (const std::string problem : {"sphere", "torus", "flat_torus", "sphere_cut"}) {
    SCOPED_TRACE(problem);
    auto run = testing::run_front(problem);
    ASSERT_TRUE(run.result.summary.is_complete()) << run.result.summary.message;
    const MeshValidation validation =
        validate(run.result.mesh, *run.setup.problem, run.setup.domain);
    expect_geometrically_valid(validation);
    EXPECT_EQ(validation.unoriented_triangle_count, 0);
  }
}

TEST(GeometricValidation, AtlasMeshOfTheTroughIsGeometricallyValid) {
  // The trough's narrow gaps (width O(ε), ε = 5e-5) need charts far smaller than elsewhere.
  auto setup = make_catalogue_problem("trough");
  AtlasOptions options;
  options.tolerance = 1e-4;
  const CoveringResult result = cover_by_atlas(*setup.problem, setup.start, setup.domain, options);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  expect_geometrically_valid(validate(result.mesh, *setup.problem, setup.domain));
}

// The catalogue's torus about the x axis (Hohmann's form), meshed on an m×k grid in its angles:
// vertices exactly on M, outward orientation.
TriangleMesh torus_about_x_axis(double R, double r, int m, int k) {
  Eigen::MatrixXd points(3, m * k);
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < k; ++j) {
      const double u = 2 * std::numbers::pi * i / m;
      const double v = 2 * std::numbers::pi * j / k;
      const Eigen::Vector3d radial(0, std::cos(u), std::sin(u));
      points.col(examples::grid_index(i, j, k)) =
          (R + r * std::cos(v)) * radial + r * std::sin(v) * Eigen::Vector3d::UnitX();
    }
  }
  std::vector<Triangle> triangles;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < k; ++j) {
      const int a = examples::grid_index(i, j, k);
      const int b = examples::grid_index((i + 1) % m, j, k);
      const int c = examples::grid_index((i + 1) % m, (j + 1) % k, k);
      const int d = examples::grid_index(i, (j + 1) % k, k);
      triangles.push_back({a, b, c});
      triangles.push_back({a, c, d});
    }
  }
  return TriangleMesh(points, triangles);
}

// A thin tube: opposite sides 0.04 apart, edges along the tube 0.05 long. Each triangle lies
// over one on the far side, which projects onto it almost entirely; they are different sheets.
TEST(GeometricValidation, OppositeSidesOfAThinTubeDoNotOverlap) {
  const Torus tube(1.0, 0.02);
  const TriangleMesh mesh = torus_about_x_axis(1.0, 0.02, 126, 12);
  const MeshValidation validation = validate(mesh, tube, Domain());
  expect_geometrically_valid(validation);
  EXPECT_EQ(validation.genus, 1);
  // Two tests on M keep the sides apart, each alone: the far side's corners stand 2r off the
  // tangent plane, so the chart's distortion bound (its curvature estimate 2·height/r²) exceeds
  // any overlap's width; and its points project back onto the far side (overlap_same_point_ratio).
  ValidationOptions blind;
  blind.overlap_same_point_ratio = 10.0;
  EXPECT_EQ(validate(mesh, tube, Domain(), blind).overlapping_pair_count, 0);
}

// A triangle across a thin tube (the stress campaign's thin_torus front case 1108): corners on
// M, two on the outer equator one edge apart along the tube and one 150° around its cross-section,
// so that its middle passes 0.06 below M, near the tube's core. Points of it project onto either
// side of the tube, so the "another sheet" rule alone would excuse it; but those points lie
// deeper than half their distance to the triangles it covers, so it follows no sheet of M.
TEST(GeometricValidation, FindsATriangleAcrossAThinTube) {
  const double r = 0.07;
  const Torus tube(1.0, r);
  const int m = 126;
  const int k = 12;  // 30° a step around the cross-section
  TriangleMesh mesh = torus_about_x_axis(1.0, r, m, k);
  Eigen::MatrixXd points = mesh.points();
  const int first = points.cols();
  points.conservativeResize(Eigen::NoChange, first + 3);
  points.col(first) = mesh.point(examples::grid_index(10, 0, k));
  points.col(first + 1) = mesh.point(examples::grid_index(12, 0, k));
  points.col(first + 2) = mesh.point(examples::grid_index(11, 5, k));
  std::vector<Triangle> triangles = mesh.triangles();
  const int across = static_cast<int>(triangles.size());
  triangles.push_back({first, first + 1, first + 2});
  const TriangleMesh planted(points, triangles);

  const MeshValidation validation = validate(planted, tube, Domain(), all_examples());
  bool found = false;
  for (const auto& [s, t] : validation.overlapping_triangle_pairs) {
    found = found || s == across || t == across;
  }
  EXPECT_TRUE(found) << validation.report();
  EXPECT_NE(validation.report().find("follows no sheet of M"), std::string::npos)
      << validation.report();
  // Without the depth rule (the validation before case 1108), fewer pairs are found: the ones
  // the depth rule adds are those the sheets rule excused.
  ValidationOptions deep = all_examples();
  deep.overlap_sheet_depth_ratio = 1e9;
  EXPECT_LT(validate(planted, tube, Domain(), deep).overlapping_pair_count,
            validation.overlapping_pair_count);
  // The tube alone, whose triangles lie on its sides, stays valid with the rule.
  expect_geometrically_valid(validate(mesh, tube, Domain()));
}

// Two concentric spheres 1e-3 apart, far less than an edge (0.035) but more than the chord
// error (1.5e-4): the mesh covers two sheets of M, not one twice.
TEST(GeometricValidation, ConcentricSpheresCloserThanAnEdgeDoNotOverlap) {
  class Shell final : public ImplicitProblem {  // (|x|² − 1)(|x|² − r²) = 0
   public:
    int ambient_dimension() const override { return 3; }
    void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                  Eigen::Ref<Eigen::VectorXd> F) const override {
      F(0) = (x.squaredNorm() - 1.0) * (x.squaredNorm() - r * r);
    }
    void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                  Eigen::Ref<Eigen::MatrixXd> J) const override {
      J.row(0) = 2.0 * x.transpose() * ((x.squaredNorm() - r * r) + (x.squaredNorm() - 1.0));
    }
    double r = 1.001;
  };
  const TriangleMesh inner = examples::icosphere(5);
  TriangleMesh outer = inner;
  for (int v = 0; v < outer.vertex_count(); ++v) {
    outer.mutable_point(v) *= 1.001;
  }
  const TriangleMesh shell = examples::disjoint_union(inner, outer);
  const MeshValidation validation = validate(shell, Shell(), Domain());
  expect_geometrically_valid(validation);
  EXPECT_EQ(validation.component_count, 2);
  ValidationOptions blind;  // as for the thin tube: the sheets are told apart on M
  blind.overlap_same_point_ratio = 10.0;
  EXPECT_GE(validate(shell, Shell(), Domain(), blind).overlapping_pair_count,
            inner.triangle_count());
}

// (e) Orientation is judged per component: a reversed component is M's other orientation.
TEST(GeometricValidation, AComponentWithReversedOrientationIsValid) {
  TriangleMesh sphere = examples::icosphere(3);
  std::vector<Triangle> reversed;
  for (Triangle tri : sphere.triangles()) {
    reversed.push_back({tri[0], tri[2], tri[1]});
  }
  TriangleMesh inside_out(sphere.points(), reversed);
  expect_geometrically_valid(validate(inside_out, Sphere(1.0), Domain()));

  // Two caps (z > 0.3 and z < -0.3) as two components, one reversed: each is oriented alike.
  std::vector<Triangle> caps;
  for (int t = 0; t < sphere.triangle_count(); ++t) {
    const double z = centroid_of(sphere, t)(2);
    if (z > 0.3) {
      caps.push_back(sphere.triangle(t));
    } else if (z < -0.3) {
      caps.push_back(reversed[t]);
    }
  }
  const MeshValidation validation =
      validate(TriangleMesh(sphere.points(), caps), Sphere(1.0), Domain());
  EXPECT_EQ(validation.component_count, 2);
  EXPECT_EQ(validation.flipped_triangle_count, 0) << validation.report();
  EXPECT_EQ(validation.overlapping_pair_count, 0) << validation.report();
}

TEST(GeometricValidation, ACombinatoriallyReversedTriangleIsNotAFoldAlongM) {
  // A triangle whose vertex order alone is reversed still covers its own part of M: it is
  // reported as an orientation inconsistency of the combinatorics, not as a geometric fold
  // (the fold test compares neighbours with the traversal directions they have).
  TriangleMesh mesh = examples::icosphere(2);
  std::vector<Triangle> triangles = mesh.triangles();
  std::swap(triangles[5][1], triangles[5][2]);
  mesh.set_triangles(triangles);
  const MeshValidation validation = validate(mesh, Sphere(1.0), Domain());
  EXPECT_TRUE(validation.flipped_triangles.empty()) << validation.report();
  EXPECT_EQ(validation.overlapping_pair_count, 0) << validation.report();
  EXPECT_GT(validation.inconsistent_orientation_count, 0);
}

TEST(GeometricValidation, RejectsBadOptionsAndDimensions) {
  const TriangleMesh mesh = examples::icosphere(1);
  ValidationOptions options;
  options.overlap_area_ratio = -1;
  EXPECT_THROW(validate(mesh, Sphere(1.0), Domain(), options), InvalidArgument);
  options = {};
  options.min_tangent_cosine = 2;
  EXPECT_THROW(validate(mesh, Sphere(1.0), Domain(), options), InvalidArgument);
  options = {};
  options.overlap_sheet_depth_ratio = 0;
  EXPECT_THROW(validate(mesh, Sphere(1.0), Domain(), options), InvalidArgument);
  options = {};
  options.crossing_plane_cosine = -0.1;
  EXPECT_THROW(validate(mesh, Sphere(1.0), Domain(), options), InvalidArgument);
  options = {};
  options.crossing_alignment = 1.5;
  EXPECT_THROW(validate(mesh, Sphere(1.0), Domain(), options), InvalidArgument);
  auto flat_torus = make_catalogue_problem("flat_torus");
  EXPECT_THROW(validate(mesh, *flat_torus.problem, Domain()), InvalidArgument);
  const Domain box4 = Domain::box(Eigen::Vector4d::Constant(-1), Eigen::Vector4d::Constant(1));
  EXPECT_THROW(validate(mesh, Sphere(1.0), box4), InvalidArgument);
}

}  // namespace
}  // namespace tessera
