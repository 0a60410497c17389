// SPDX-License-Identifier: MIT
// Edge swaps on meshes of M: the Delaunay-type swaps never lower the minimum angle; every
// criterion keeps validity, the Euler characteristic, the boundary and the orientation, even
// after random swaps; a non-convex quadrilateral is never swapped; the sweeps terminate.
#include "tessera/methods/improvement/edge_swap.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "support/front_run.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

using testing::FrontRun;
using testing::run_front;

// Boundary edges as sorted vertex pairs, sorted: the boundary is the same iff these are equal.
std::vector<MeshTopology::Edge> boundary_edges(const TriangleMesh& mesh) {
  const MeshTopology topology(mesh);
  std::vector<MeshTopology::Edge> edges;
  for (const int e : topology.boundary_edges()) {
    edges.push_back(topology.edge(e));
  }
  std::sort(edges.begin(), edges.end());
  return edges;
}

// True if no triangle needs reversing to agree with its neighbours (triangle 0 is kept).
bool is_consistently_oriented(const TriangleMesh& mesh) {
  const OrientationAssignment assignment = MeshTopology(mesh).orientation_assignment();
  return std::none_of(assignment.is_flipped.begin(), assignment.is_flipped.end(),
                      [](std::uint8_t flipped) { return flipped != 0; });
}

// Makes `attempts` random swaps that check_edge_swap allows, whatever they do to the shape.
int scramble(TriangleMesh& mesh, const ImplicitProblem& problem, int attempts, unsigned seed) {
  std::mt19937 random(seed);
  int swaps = 0;
  for (int i = 0; i < attempts; ++i) {
    const int t = static_cast<int>(random() % static_cast<unsigned>(mesh.triangle_count()));
    const int k = static_cast<int>(random() % 3);
    const Triangle triangle = mesh.triangle(t);
    if (swap_edge(mesh, problem, triangle[k], triangle[(k + 1) % 3]) == SwapCheck::Allowed) {
      ++swaps;
    }
  }
  return swaps;
}

TEST(EdgeSwap, DelaunaySwapsOnCutSphereDoNotLowerMinAngleAndKeepTheMesh) {
  FrontRun run = run_front("sphere_cut", 0.3);
  const ImplicitProblem& problem = *run.setup.problem;
  const MeshValidation validation_before = validate(run.result.mesh);
  ASSERT_TRUE(validation_before.is_valid()) << validation_before.report();
  const MeshQuality quality_before = measure_quality(run.result.mesh, problem);
  const auto boundary_before = boundary_edges(run.result.mesh);

  const ImprovementSummary summary = improve_by_edge_swaps(
      run.result.mesh, problem, {.criterion = ImprovementCriterion::MaxMinAngle});
  std::printf("sphere_cut h = 0.3, angle: %s\n", summary.brief_report().c_str());

  const MeshValidation validation_after = validate(run.result.mesh);
  EXPECT_TRUE(validation_after.is_valid()) << validation_after.report();
  EXPECT_EQ(validation_after.euler_characteristic, validation_before.euler_characteristic);
  EXPECT_EQ(boundary_edges(run.result.mesh), boundary_before);
  EXPECT_TRUE(is_consistently_oriented(run.result.mesh));
  EXPECT_TRUE(summary.converged);
  const MeshQuality quality_after = measure_quality(run.result.mesh, problem);
  // Each swap raises the smallest of its six angles (measured in R^n, as here) and leaves every
  // other triangle alone, so the global minimum cannot drop: exact, up to the angle rounding.
  EXPECT_GE(quality_after.min_angle_degrees, quality_before.min_angle_degrees - 1e-9);
  EXPECT_DOUBLE_EQ(summary.min_angle_degrees_after, quality_after.min_angle_degrees);
  // Vertices do not move, and a new triangle spans the same quadrilateral as the two old ones,
  // whose centroids are O(κ h²) from M; the new centroids are in the same quadrilateral, so
  // their distance is the same order. 1.5 bounds the change of the constant (a swap makes the
  // triangles rounder, so it does not lengthen the longest edge much); not a sharp bound.
  EXPECT_LE(quality_after.centroid_distance.max, 1.5 * quality_before.centroid_distance.max);
  EXPECT_EQ(quality_after.failed_projections, 0);
}

class EdgeSwapStress : public ::testing::TestWithParam<std::string> {};

TEST_P(EdgeSwapStress, RandomSwapsThenEveryCriterionKeepValidityTopologyAndOrientation) {
  const FrontRun run = run_front(GetParam());
  const ImplicitProblem& problem = *run.setup.problem;
  const MeshValidation original = validate(run.result.mesh);
  ASSERT_TRUE(original.is_valid()) << original.report();
  const auto boundary = boundary_edges(run.result.mesh);

  TriangleMesh scrambled = run.result.mesh;
  const int random_swaps = scramble(scrambled, problem, 3 * scrambled.triangle_count(), 5);
  EXPECT_GT(random_swaps, scrambled.triangle_count() / 4);  // the stress is real
  const MeshValidation after_scramble = validate(scrambled);
  ASSERT_TRUE(after_scramble.is_valid()) << after_scramble.report();
  EXPECT_EQ(after_scramble.euler_characteristic, original.euler_characteristic);
  EXPECT_EQ(boundary_edges(scrambled), boundary);
  EXPECT_TRUE(is_consistently_oriented(scrambled));
  const double scrambled_min_angle = measure_shape(scrambled).min_angle_degrees;

  for (const ImprovementCriterion criterion :
       {ImprovementCriterion::MaxMinAngle, ImprovementCriterion::NormalAngle,
        ImprovementCriterion::MidpointDistance}) {
    SCOPED_TRACE(to_string(criterion));
    TriangleMesh mesh = scrambled;
    const ImprovementSummary summary =
        improve_by_edge_swaps(mesh, problem, {.criterion = criterion});
    std::printf("%s scrambled by %d swaps, %s: %s\n", GetParam().c_str(), random_swaps,
                to_string(criterion), summary.brief_report().c_str());
    EXPECT_GT(summary.swaps, 0);
    const MeshValidation validation = validate(mesh);
    EXPECT_TRUE(validation.is_valid()) << validation.report();
    EXPECT_EQ(validation.euler_characteristic, original.euler_characteristic);
    EXPECT_EQ(validation.triangle_count, original.triangle_count);
    EXPECT_EQ(validation.edge_count, original.edge_count);
    EXPECT_EQ(boundary_edges(mesh), boundary);
    EXPECT_TRUE(is_consistently_oriented(mesh));
    // Termination: the procedure stops by itself, well before the cap.
    EXPECT_TRUE(summary.converged);
    EXPECT_LT(summary.sweeps, ImprovementOptions{}.max_sweeps);
    if (criterion == ImprovementCriterion::MaxMinAngle) {
      EXPECT_GT(summary.min_angle_degrees_after, scrambled_min_angle);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(FrontMeshes, EdgeSwapStress, ::testing::Values("torus", "sphere_cut"));

TEST_P(EdgeSwapStress, DelaunaySwapsUndoALightScramble) {
  // A few random swaps (0.3 per triangle) make slivers but no folds; Lawson's procedure with the
  // max-min angle criterion then finds a triangulation at least as good as the front's (on the
  // plane it would be the Delaunay triangulation; here the front's mesh is near-Delaunay).
  const FrontRun run = run_front(GetParam());
  const ImplicitProblem& problem = *run.setup.problem;
  const double original_min_angle = measure_shape(run.result.mesh).min_angle_degrees;
  TriangleMesh mesh = run.result.mesh;
  scramble(mesh, problem, 3 * mesh.triangle_count() / 10, 7);
  ASSERT_LT(measure_shape(mesh).min_angle_degrees, original_min_angle - 5.0);
  const ImprovementSummary summary = improve_by_edge_swaps(mesh, problem);
  EXPECT_TRUE(summary.converged);
  EXPECT_GE(summary.min_angle_degrees_after, original_min_angle - 1e-9);
  EXPECT_TRUE(validate(mesh).is_valid());
}

TEST(EdgeSwap, SweepCapIsRespected) {
  const FrontRun run = run_front("torus");
  TriangleMesh mesh = run.result.mesh;
  scramble(mesh, *run.setup.problem, 3 * mesh.triangle_count(), 11);
  const ImprovementSummary summary =
      improve_by_edge_swaps(mesh, *run.setup.problem, {.max_sweeps = 1});
  EXPECT_EQ(summary.sweeps, 1);
  EXPECT_FALSE(summary.converged);  // one sweep cannot undo thousands of random swaps
  EXPECT_TRUE(validate(mesh).is_valid());
}

// A stop request ends the swaps at once (a covering's Ctrl-C), keeping those made, each checked.
TEST(EdgeSwap, StopRequestEndsTheSwapsWithAValidMesh) {
  const FrontRun run = run_front("torus");
  TriangleMesh scrambled = run.result.mesh;
  scramble(scrambled, *run.setup.problem, 3 * scrambled.triangle_count() / 10, 7);
  TriangleMesh whole = scrambled;
  const ImprovementSummary finished = improve_by_edge_swaps(whole, *run.setup.problem);
  ASSERT_GT(finished.swaps, 20);
  int polls = 0;
  ImprovementOptions options;
  options.stop_requested = [&polls] { return ++polls > 200; };
  TriangleMesh stopped = scrambled;
  const ImprovementSummary summary = improve_by_edge_swaps(stopped, *run.setup.problem, options);
  EXPECT_TRUE(summary.interrupted);
  EXPECT_FALSE(summary.converged);
  EXPECT_EQ(polls, 201);
  EXPECT_LT(summary.swaps, finished.swaps);
  EXPECT_TRUE(validate(stopped, *run.setup.problem, run.setup.domain).is_valid());
}

// Two triangles in the plane z = 0: (a, b, c) and (b, a, d), both counter-clockwise.
TriangleMesh two_triangles(const Eigen::Vector3d& d) {
  Eigen::MatrixXd points(3, 4);
  points.col(0) = Eigen::Vector3d(0, 0, 0);  // a
  points.col(1) = Eigen::Vector3d(2, 0, 0);  // b
  points.col(2) = Eigen::Vector3d(1, 1, 0);  // c
  points.col(3) = d;
  return TriangleMesh(points, {{0, 1, 2}, {1, 0, 3}});
}

TEST(EdgeSwap, NonConvexQuadrilateralIsNeverSwapped) {
  const ProblemSetup plane = make_catalogue_problem("plane");
  // d = (3, −0.5): the diagonal cd passes beside b, so a, d, b, c has a reflex corner at b and
  // the swapped triangle (d, b, c) would be flipped.
  TriangleMesh mesh = two_triangles(Eigen::Vector3d(3, -0.5, 0));
  const auto triangles = mesh.triangles();
  EXPECT_EQ(check_edge_swap(mesh, *plane.problem, 0, 1), SwapCheck::NonConvex);
  EXPECT_EQ(swap_edge(mesh, *plane.problem, 0, 1), SwapCheck::NonConvex);
  EXPECT_EQ(mesh.triangles(), triangles);
  for (const ImprovementCriterion criterion :
       {ImprovementCriterion::MaxMinAngle, ImprovementCriterion::NormalAngle,
        ImprovementCriterion::MidpointDistance}) {
    const ImprovementSummary summary = improve_by_edge_swaps(
        mesh, *plane.problem, {.criterion = criterion, .relative_tolerance = 0.0});
    EXPECT_EQ(summary.swaps, 0);
    EXPECT_EQ(mesh.triangles(), triangles);
  }
  // d exactly on the line through c and b: the quadrilateral is convex but not strictly.
  TriangleMesh flat_corner = two_triangles(Eigen::Vector3d(3, -1, 0));
  EXPECT_EQ(check_edge_swap(flat_corner, *plane.problem, 0, 1), SwapCheck::NonConvex);
  // Boundary edges are never candidates.
  EXPECT_EQ(check_edge_swap(mesh, *plane.problem, 0, 2), SwapCheck::BoundaryEdge);
  EXPECT_EQ(check_edge_swap(mesh, *plane.problem, 2, 3), SwapCheck::NotAnEdge);
}

// Quadrilaterals a, d, b, c that are not convex seen from the plane z = 0 (M), each built so
// that its criterion prefers the other diagonal: the criterion is evaluated first, and the
// convexity check must still refuse. rejected_non_convex counts only swaps the criterion
// wanted, so its value 1 says both: the criterion wanted the swap, the check refused it.
TEST(EdgeSwap, NonConvexQuadrilateralIsRefusedEvenWhenTheCriterionWantsTheSwap) {
  const ProblemSetup plane = make_catalogue_problem("plane");
  const auto quadrilateral = [](double a_z, const Eigen::Vector3d& c, const Eigen::Vector3d& d) {
    Eigen::MatrixXd points(3, 4);
    points.col(0) = Eigen::Vector3d(0, 0, a_z);  // a
    points.col(1) = Eigen::Vector3d(2, 0, a_z);  // b
    points.col(2) = c;
    points.col(3) = d;
    return TriangleMesh(points, {{0, 1, 2}, {1, 0, 3}});
  };
  // Seen from above, c = (1, 1), d = (4, −0.5): the diagonal cd crosses y = 0 at x = 3, beside
  // the edge ab, so the corner at b is reflex.
  const struct {
    ImprovementCriterion criterion;
    TriangleMesh mesh;
    const char* why_the_criterion_wants_it;
  } cases[] = {
      {ImprovementCriterion::MaxMinAngle, quadrilateral(0, {1, 1, 0}, {4, -0.5, 0}),
       "smallest angle 7.1° (at a in bad) before, 12.5° after (unsigned angles)"},
      {ImprovementCriterion::NormalAngle, quadrilateral(0, {1, 1, 3}, {4, -0.5, 8}),
       "angle between the normals 158° before, 143° after"},
      {ImprovementCriterion::MidpointDistance, quadrilateral(0.1, {1, 1, 0}, {4, -0.5, 0}),
       "midpoint of ab 0.1 above M, midpoint of cd on M"},
  };
  for (const auto& [criterion, start, why] : cases) {
    TriangleMesh mesh = start;
    EXPECT_EQ(check_edge_swap(mesh, *plane.problem, 0, 1), SwapCheck::NonConvex) << why;
    const ImprovementSummary summary = improve_by_edge_swaps(
        mesh, *plane.problem, {.criterion = criterion, .relative_tolerance = 0.0});
    EXPECT_EQ(summary.swaps, 0) << to_string(criterion);
    EXPECT_EQ(summary.rejected_non_convex, 1) << to_string(criterion) << ": " << why;
    EXPECT_EQ(mesh.triangles(), start.triangles()) << to_string(criterion);
  }
}

TEST(EdgeSwap, ConvexQuadrilateralIsSwappedWithOrientationKept) {
  const ProblemSetup plane = make_catalogue_problem("plane");
  // d = (1, −0.2): abc and bad are thin-ish; the diagonal cd gives rounder triangles.
  TriangleMesh mesh = two_triangles(Eigen::Vector3d(1, -0.2, 0));
  EXPECT_EQ(check_edge_swap(mesh, *plane.problem, 0, 1), SwapCheck::Allowed);
  const ImprovementSummary summary = improve_by_edge_swaps(mesh, *plane.problem);
  EXPECT_EQ(summary.swaps, 1);
  EXPECT_GT(summary.min_angle_degrees_after, summary.min_angle_degrees_before);
  // The new triangles are (c, a, d) and (d, b, c): counter-clockwise like the old ones.
  const std::vector<Triangle> expected = {{2, 0, 3}, {3, 1, 2}};
  EXPECT_EQ(mesh.triangles(), expected);
  EXPECT_TRUE(validate(mesh).is_valid());
  EXPECT_TRUE(is_consistently_oriented(mesh));
}

TEST(EdgeSwap, BadOptionsAreRefused) {
  const ProblemSetup plane = make_catalogue_problem("plane");
  TriangleMesh mesh = two_triangles(Eigen::Vector3d(1, -1, 0));
  EXPECT_THROW(improve_by_edge_swaps(mesh, *plane.problem, {.max_sweeps = 0}), InvalidArgument);
  EXPECT_THROW(improve_by_edge_swaps(mesh, *plane.problem, {.relative_tolerance = -1}),
               InvalidArgument);
  TriangleMesh wrong_dimension(Eigen::MatrixXd::Zero(4, 3), {{0, 1, 2}});
  EXPECT_THROW(improve_by_edge_swaps(wrong_dimension, *plane.problem), InvalidArgument);
}

}  // namespace
}  // namespace tessera
