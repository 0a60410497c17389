// SPDX-License-Identifier: MIT
// validate() on a split mesh: every rank holds its rows of every vertex (TriangleMesh::set_space,
// Domain::distributed) and the checks reduce through the DistributedSpace (the SPMD design of
// docs/cluster.md). The verdict must be the one process's, defect for defect, on any number of
// ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <memory>
#include <vector>

#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/mesh_quality.h"
#include "tessera/geometry/mesh_topology.h"
#include "tessera/geometry/mesh_validation.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/catalogue.h"

namespace tessera::petsc {
namespace {

// A covering of bratu2d:N=6 with three kinds of defect put in: two neighbouring vertices that
// trade places (their triangles fold over), a triangle across a vertex's fan (it overlaps the
// fan), and an unreferenced vertex outside the domain (λ below its bound).
TriangleMesh defective_mesh(const ProblemSetup& setup) {
  MethodSettings settings;
  settings.step = 0.3;
  const CoveringResult covered = cover(setup, find_covering_method("atlas"), settings);
  EXPECT_TRUE(covered.summary.is_complete()) << covered.summary.message;
  TriangleMesh mesh = covered.mesh;
  const MeshTopology topology(mesh.vertex_count(), mesh.triangles());
  // An interior vertex with a full fan of at least five triangles.
  int hub = -1;
  for (int v = 0; v < mesh.vertex_count() && hub < 0; ++v) {
    const auto around = topology.vertex_triangles(v);
    bool interior = around.size() >= 5;
    for (int t : around) {
      for (int e : topology.triangle_edges(t)) {
        interior = interior && topology.edge_triangles(e).size() == 2;
      }
    }
    hub = interior ? v : -1;
  }
  EXPECT_GE(hub, 0);
  std::vector<Triangle> triangles = mesh.triangles();
  // Across the fan: the third vertices of three of its triangles.
  std::vector<int> ring;
  for (int t : topology.vertex_triangles(hub)) {
    for (int w : triangles[t]) {
      if (w != hub && std::find(ring.begin(), ring.end(), w) == ring.end()) {
        ring.push_back(w);
      }
    }
  }
  triangles.push_back({ring[0], ring[2], ring[4]});
  mesh.set_triangles(triangles);
  // Folded: two neighbouring vertices far from the hub trade places (both stay on M).
  const Triangle far = triangles[static_cast<std::size_t>(topology.triangle_count() / 2)];
  const Eigen::VectorXd a = mesh.point(far[0]);
  mesh.mutable_point(far[0]) = mesh.point(far[1]);
  mesh.mutable_point(far[1]) = a;
  Eigen::VectorXd outside = mesh.point(hub);
  outside(outside.size() - 2) = 0.25;  // λ ≥ 0.5 in the catalogue's box
  mesh.add_vertex(outside);
  return mesh;
}

TEST(DistributedValidation, ASplitMeshIsJudgedAsInOneProcess) {
  const ProblemSetup setup = make_catalogue_problem("bratu2d:N=6");
  const TriangleMesh mesh = defective_mesh(setup);
  const MeshValidation serial = validate(mesh, *setup.problem, setup.domain);
  ASSERT_FALSE(serial.is_valid());
  EXPECT_GE(serial.flipped_triangle_count, 1);
  EXPECT_GE(serial.overlapping_pair_count, 1);
  EXPECT_EQ(serial.vertex_outside_domain_count, 1);

  // The same mesh on the PETSc problem in the metric's coordinates, split over the ranks.
  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 2, 6);
  const ScaledPetscProblem scaled(bratu);
  const DistributedProblem distributed(scaled);
  const std::shared_ptr<const AmbientSpace> space = distributed.space();
  const Eigen::VectorXd weights = metric_weights(*setup.problem);
  ASSERT_GT(weights.size(), 0);
  const int first = space->first_row();
  const int rows = space->local_rows();
  Eigen::MatrixXd local(rows, mesh.vertex_count());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    local.col(v) = weights.cwiseProduct(mesh.point(v)).segment(first, rows);
  }
  TriangleMesh split(local, mesh.triangles());
  split.set_space(space);
  const Domain split_domain = scale_domain(setup.domain, weights).distributed(space);
  const MeshValidation result = validate(split, distributed, split_domain);

  EXPECT_EQ(result.ambient_dimension, serial.ambient_dimension);
  EXPECT_EQ(result.euler_characteristic, serial.euler_characteristic);
  EXPECT_EQ(result.inconsistent_orientation_count, serial.inconsistent_orientation_count);
  EXPECT_EQ(result.unreferenced_vertex_count, serial.unreferenced_vertex_count);
  EXPECT_EQ(result.degenerate_triangle_count, serial.degenerate_triangle_count);
  EXPECT_EQ(result.flipped_triangles, serial.flipped_triangles);
  EXPECT_EQ(result.overlapping_triangle_pairs, serial.overlapping_triangle_pairs);
  EXPECT_EQ(result.vertices_outside_domain, serial.vertices_outside_domain);
  EXPECT_EQ(result.unoriented_triangle_count, serial.unoriented_triangle_count);
  // The messages name the same places (coordinates gathered from the ranks).
  EXPECT_EQ(result.report(), serial.report());
}

// The report's measures of a split mesh: shapes from the triangles' Gram matrices summed over
// the ranks, distances to M by the distributed correctors.
TEST(DistributedQuality, ASplitMeshMeasuresAsInOneProcess) {
  const ProblemSetup setup = make_catalogue_problem("bratu2d:N=6");
  MethodSettings settings;
  settings.step = 0.3;
  const CoveringResult covered = cover(setup, find_covering_method("atlas"), settings);
  ASSERT_TRUE(covered.summary.is_complete()) << covered.summary.message;
  const TriangleMesh& mesh = covered.mesh;
  QualityOptions options;
  options.max_samples = 40;
  options.max_seconds = std::numeric_limits<double>::infinity();  // every rank samples alike
  const MeshQuality serial = measure_quality(mesh, *setup.problem, options);

  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 2, 6);
  const ScaledPetscProblem scaled(bratu);
  const DistributedProblem distributed(scaled);
  const std::shared_ptr<const AmbientSpace> space = distributed.space();
  const Eigen::VectorXd weights = metric_weights(*setup.problem);
  Eigen::MatrixXd local(space->local_rows(), mesh.vertex_count());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    local.col(v) = weights.cwiseProduct(mesh.point(v)).segment(space->first_row(),
                                                                space->local_rows());
  }
  TriangleMesh split(local, mesh.triangles());
  split.set_space(space);
  const MeshQuality result = measure_quality(split, distributed, options);

  EXPECT_NEAR(result.area, serial.area, 1e-12 * serial.area);
  EXPECT_NEAR(result.min_angle_degrees, serial.min_angle_degrees, 1e-9);
  EXPECT_NEAR(result.max_angle_degrees, serial.max_angle_degrees, 1e-9);
  EXPECT_EQ(result.fraction_angles_below_30, serial.fraction_angles_below_30);
  EXPECT_NEAR(result.min_edge_length, serial.min_edge_length, 1e-12);
  EXPECT_NEAR(result.max_edge_length, serial.max_edge_length, 1e-12);
  EXPECT_LE(result.vertex_residual.max, 1e-9);
  EXPECT_EQ(result.failed_projections, 0);
  // The serial report corrects its corner chord's foot towards M's normal; the split one
  // projects by Gauss–Newton: the same distances to a few per cent.
  EXPECT_EQ(result.centroid_distance.count, serial.centroid_distance.count);
  EXPECT_NEAR(result.centroid_distance.max, serial.centroid_distance.max,
              0.05 * serial.centroid_distance.max);
  EXPECT_NEAR(result.midpoint_distance.max, serial.midpoint_distance.max,
              0.05 * serial.midpoint_distance.max);
}

// A split mesh of a distributed problem must say so; the check names what is missing.
TEST(DistributedValidation, AMeshThatHoldsWholePointsIsRefusedForADistributedProblem) {
  const ProblemSetup setup = make_catalogue_problem("bratu2d:N=6");
  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, 2, 6);
  const ScaledPetscProblem scaled(bratu);
  const DistributedProblem distributed(scaled);
  const std::shared_ptr<const AmbientSpace> space = distributed.space();
  if (space->local_rows() == space->dimension()) {
    GTEST_SKIP() << "one rank: whole points are this rank's rows";
  }
  TriangleMesh whole(Eigen::MatrixXd::Zero(space->dimension(), 3), {{0, 1, 2}});
  EXPECT_THROW(validate(whole, distributed, setup.domain), InvalidArgument);
}

}  // namespace
}  // namespace tessera::petsc
