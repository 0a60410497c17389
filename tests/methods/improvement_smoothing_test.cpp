// SPDX-License-Identifier: MIT
// Tangential smoothing on M: vertices stay on M, boundary vertices do not move, the mesh stays
// valid with the same triangles, and the minimum angle does not drop.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <random>
#include <string>
#include <vector>

#include "tessera/core/corrector.h"
#include "tessera/core/error.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/front/advancing_front.h"
#include "tessera/methods/improvement/edge_swap.h"
#include "tessera/methods/improvement/tangential_smoothing.h"
#include "tessera/problems/catalogue.h"

namespace tessera {
namespace {

class TangentialSmoothing : public ::testing::TestWithParam<std::string> {};

TEST_P(TangentialSmoothing, KeepsTheMeshOnMValidAndDoesNotLowerTheMinAngle) {
  const ProblemSetup setup = make_catalogue_problem(GetParam());
  const ImplicitProblem& problem = *setup.problem;
  FrontOptions front;
  front.step = GetParam() == "sphere_cut" ? 0.3 : setup.suggested_step;
  TriangleMesh mesh = triangulate_by_front(problem, setup.start, setup.domain, front).mesh;
  // A few random swaps make a rougher start, so that smoothing has work to do.
  std::mt19937 random(3);
  for (int i = 0; i < mesh.triangle_count() / 5; ++i) {
    const Triangle t = mesh.triangle(static_cast<int>(random() % mesh.triangle_count()));
    const int k = static_cast<int>(random() % 3);
    swap_edge(mesh, problem, t[k], t[(k + 1) % 3]);
  }
  const TriangleMesh before = mesh;
  const MeshValidation validation_before = validate(before);
  ASSERT_TRUE(validation_before.is_valid()) << validation_before.report();
  const MeshQuality quality_before = measure_quality(before, problem);

  const SmoothingSummary summary = smooth_tangentially(mesh, problem, {.iterations = 5});
  std::printf("%s: %s\n", GetParam().c_str(), summary.brief_report().c_str());
  EXPECT_GT(summary.moves, 0);

  EXPECT_EQ(mesh.triangles(), before.triangles());
  const MeshValidation validation = validate(mesh);
  EXPECT_TRUE(validation.is_valid()) << validation.report();
  EXPECT_EQ(validation.euler_characteristic, validation_before.euler_characteristic);
  const MeshQuality quality = measure_quality(mesh, problem);
  // Moved vertices are corrector end points: ‖F‖ ≤ residual_tolerance (1e-9), ×10 for rounding.
  EXPECT_LE(quality.vertex_residual.max, 10 * CorrectorOptions{}.residual_tolerance);
  // Each accepted move keeps its star's smallest angle, so the global minimum cannot drop.
  EXPECT_GE(quality.min_angle_degrees, quality_before.min_angle_degrees - 1e-9);
  // Boundary vertices are fixed.
  const MeshTopology topology(before);
  for (const int e : topology.boundary_edges()) {
    for (const int v : topology.edge(e)) {
      EXPECT_EQ(mesh.point(v), before.point(v)) << "boundary vertex " << v << " moved";
    }
  }
  const OrientationAssignment orientation = MeshTopology(mesh).orientation_assignment();
  EXPECT_TRUE(std::none_of(orientation.is_flipped.begin(), orientation.is_flipped.end(),
                           [](std::uint8_t flipped) { return flipped != 0; }));
}

INSTANTIATE_TEST_SUITE_P(FrontMeshes, TangentialSmoothing,
                         ::testing::Values("sphere_cut", "torus"));

TEST(TangentialSmoothingFold, AMoveThatFoldsATriangleIsRefused) {
  const ProblemSetup plane = make_catalogue_problem("plane");
  // Vertex 0 at the origin, its star a non-convex pentagon with a notch at (−0.3, 0): the
  // average of the neighbours, (−1.66, 0), lies beyond the notch, so moving toward it (ω = 0.5:
  // to (−0.83, 0)) flips the triangles (0, 3, 4) and (0, 4, 5). The angle test is off, so only
  // the fold test can refuse the move.
  Eigen::MatrixXd points(3, 6);
  points << 0, 1, 1, -5, -0.3, -5,  //
      0, -1, 1, 1, 0, -1,           //
      0, 0, 0, 0, 0, 0;
  TriangleMesh mesh(points, {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 5}, {0, 5, 1}});
  ASSERT_TRUE(validate(mesh).is_valid());
  const SmoothingSummary summary =
      smooth_tangentially(mesh, *plane.problem, {.iterations = 1, .keep_min_angle = false});
  EXPECT_EQ(summary.moves, 0);
  EXPECT_EQ(summary.rejected_fold, 1);
  EXPECT_EQ(mesh.point(0), points.col(0));
}

TEST(TangentialSmoothingOptions, BadOptionsAreRefused) {
  const ProblemSetup plane = make_catalogue_problem("plane");
  TriangleMesh mesh(Eigen::MatrixXd::Identity(3, 3), {{0, 1, 2}});
  EXPECT_THROW(smooth_tangentially(mesh, *plane.problem, {.iterations = -1}), InvalidArgument);
  EXPECT_THROW(smooth_tangentially(mesh, *plane.problem, {.relaxation = 0}), InvalidArgument);
}

}  // namespace
}  // namespace tessera
