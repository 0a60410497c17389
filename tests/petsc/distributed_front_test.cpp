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
#include "petsc/split_support.h"

namespace tessera::petsc {
namespace {

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
  const ProblemSetup split = split_setup(serial, scaled);
  const DistributedSpace& space = distributed_space(*split.problem->space());
  const long reductions_before = space.reductions();
  const CoveringResult result = cover(split, front, settings);
  ASSERT_TRUE(result.summary.is_complete()) << result.summary.message;
  // The covering's collective calls (the solver's own are PETSc's), each of a few numbers.
  const double per_vertex =
      static_cast<double>(space.reductions() - reductions_before) / result.mesh.vertex_count();
  ::testing::Test::RecordProperty("reductions_per_vertex_" + specification,
                                  std::to_string(per_vertex));
  EXPECT_LE(per_vertex, 400.0);

  expect_same_covering(result, expected, weights);
  EXPECT_EQ(result.summary.step, expected.summary.step);
  EXPECT_EQ(result.summary.merges, expected.summary.merges);
  EXPECT_EQ(result.summary.step_reductions, expected.summary.step_reductions);
  EXPECT_EQ(result.summary.front_connections, expected.summary.front_connections);
}

// bvp (1-D, n = 32) and bratu2d (2-D, n = 38), the front's default order (smallest gap first,
// the tangent bases of new vertices from their creator's factorisation).
TEST(DistributedFront, TheCoveringOfSplitStatesIsTheOneProcessMesh) {
  expect_one_process_mesh("bvp:points=30", 1, 30, 0.2, 0.1);
  expect_one_process_mesh("bratu2d:N=6", 2, 6, 0.2, 0.1);
}

}  // namespace
}  // namespace tessera::petsc
