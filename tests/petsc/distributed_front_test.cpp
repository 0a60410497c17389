// SPDX-License-Identifier: MIT
// The advancing front on split points: every rank holds its rows of every vertex and tangent
// basis, and the front's geometry (tangent coordinates of the fans, gap angles, distances, the
// proximity grid's view, the domain's distances) is reduced over the ranks (the SPMD design of
// docs/cluster.md). The covering must be the one process's on any number of ranks.
#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "tessera/core/scaled_problem.h"
#include "tessera/methods/covering_methods.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/catalogue.h"

namespace tessera::petsc {
namespace {

const DistributedSpace& distributed_space(const AmbientSpace& space) {
  return dynamic_cast<const DistributedSpace&>(space);
}

// The catalogue's problem where λ and ε lie within `half_width` of the start's: a few hundred
// vertices, few enough for MUMPS's set-up per factorisation on three ranks.
ProblemSetup around_start(const std::string& specification, double half_width) {
  ProblemSetup setup = make_catalogue_problem(specification);
  const int n = setup.problem->ambient_dimension();
  for (const int coordinate : {n - 2, n - 1}) {
    for (const double side : {-1.0, 1.0}) {
      Eigen::VectorXd normal = Eigen::VectorXd::Zero(n);
      normal(coordinate) = -side;
      Eigen::VectorXd point = Eigen::VectorXd::Zero(n);
      point(coordinate) = setup.start(coordinate) + half_width * side;
      setup.domain.add_half_space(normal, point);
    }
  }
  return setup;
}

// The whole pipeline (start, front, clipping, notches, swaps, refinement to the tolerance,
// validation, the checks) on split states against one process, in y = W x.
void expect_one_process_mesh(const std::string& specification, int spatial_dimension,
                             int grid_size, double step, double half_width) {
  SCOPED_TRACE(specification);
  const ProblemSetup serial = around_start(specification, half_width);
  const Eigen::VectorXd weights = metric_weights(*serial.problem);
  ASSERT_GT(weights.size(), 0);
  MethodSettings settings;
  settings.step = step;
  const CoveringMethod& front = find_covering_method("front");
  const CoveringResult expected = cover(serial, front, settings);
  ASSERT_TRUE(expected.summary.is_complete()) << expected.summary.message;
  ASSERT_GT(expected.mesh.vertex_count(), 50);

  PetscArrheniusBratu bratu(PETSC_COMM_WORLD, spatial_dimension, grid_size);
  const ScaledPetscProblem scaled(bratu);
  ProblemSetup split;
  split.problem = std::make_unique<DistributedProblem>(scaled);
  const std::shared_ptr<const AmbientSpace> space = split.problem->space();
  const int first = space->first_row();
  const int rows = space->local_rows();
  split.start = weights.cwiseProduct(serial.start).segment(first, rows);
  split.domain = scale_domain(serial.domain, weights).distributed(space);
  split.suggested_step = serial.suggested_step;
  const long reductions_before = distributed_space(*space).reductions();
  const CoveringResult result = cover(split, front, settings);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  // The covering's collective calls (the solver's own are PETSc's), each of a few numbers.
  const double per_vertex =
      static_cast<double>(distributed_space(*space).reductions() - reductions_before) /
      result.mesh.vertex_count();
  ::testing::Test::RecordProperty("reductions_per_vertex_" + specification,
                                  std::to_string(per_vertex));
  EXPECT_LE(per_vertex, 400.0);

  EXPECT_TRUE(result.mesh.space().is_distributed());
  EXPECT_EQ(result.mesh.ambient_dimension(), rows);
  ASSERT_EQ(result.mesh.vertex_count(), expected.mesh.vertex_count());
  EXPECT_EQ(result.mesh.triangles(), expected.mesh.triangles());
  double largest_gap = 0.0;
  for (int v = 0; v < result.mesh.vertex_count(); ++v) {
    const Eigen::VectorXd gap =
        result.mesh.point(v) - weights.cwiseProduct(expected.mesh.point(v)).segment(first, rows);
    largest_gap = std::max(largest_gap, space->norm(gap));
  }
  EXPECT_LE(largest_gap, 1e-7);
  EXPECT_EQ(result.summary.step, expected.summary.step);
  EXPECT_EQ(result.summary.merges, expected.summary.merges);
  EXPECT_EQ(result.summary.step_reductions, expected.summary.step_reductions);
  EXPECT_EQ(result.summary.front_connections, expected.summary.front_connections);
  EXPECT_EQ(result.summary.refined_edges, expected.summary.refined_edges);
  EXPECT_EQ(result.summary.notes, expected.summary.notes);
  EXPECT_EQ(result.summary.factorisations, expected.summary.factorisations);
  EXPECT_EQ(result.summary.jacobian_evaluations, expected.summary.jacobian_evaluations);
  EXPECT_EQ(result.summary.function_evaluations, expected.summary.function_evaluations);
  ASSERT_TRUE(result.validation.has_value());
  EXPECT_TRUE(result.validation->is_valid()) << result.validation->report();
}

// bvp (1-D, n = 32) and bratu2d (2-D, n = 38), the front's default order (smallest gap first,
// the tangent bases of new vertices from their creator's factorisation).
TEST(DistributedFront, TheCoveringOfSplitStatesIsTheOneProcessMesh) {
  expect_one_process_mesh("bvp:points=30", 1, 30, 0.2, 0.1);
  expect_one_process_mesh("bratu2d:N=6", 2, 6, 0.2, 0.1);
}

}  // namespace
}  // namespace tessera::petsc
