// SPDX-License-Identifier: MIT
// The tests' ways to put a serial problem, mesh or covering on split states (each rank its rows
// of every n-vector) and to compare what the ranks make with what one process makes.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <memory>
#include <string>

#include "tessera/core/ambient_space.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/geometry/triangle_mesh.h"
#include "tessera/methods/covering_result.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/problems/catalogue.h"

namespace tessera::petsc {

/// This rank's rows (space's split) of every vertex of `mesh`, the same triangles.
inline TriangleMesh split_rows(const TriangleMesh& mesh,
                               const std::shared_ptr<const AmbientSpace>& space) {
  Eigen::MatrixXd local(space->local_rows(), mesh.vertex_count());
  for (int v = 0; v < mesh.vertex_count(); ++v) {
    local.col(v) = mesh.point(v).segment(space->first_row(), space->local_rows());
  }
  TriangleMesh rows(local, mesh.triangles());
  rows.set_space(space);
  return rows;
}

inline const DistributedSpace& distributed_space(const AmbientSpace& space) {
  return dynamic_cast<const DistributedSpace&>(space);
}

/// The catalogue's problem where λ and ε lie within `half_width` of the start's: a few hundred
/// vertices, few enough for MUMPS's set-up per factorisation on several ranks.
inline ProblemSetup around_start(const std::string& specification, double half_width) {
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

/// `serial` on split states, in its metric's coordinates y = W x: the problem over `scaled`
/// (which must outlive it), this rank's rows of the start and the domain.
inline ProblemSetup split_setup(const ProblemSetup& serial, const PetscProblem& scaled) {
  const Eigen::VectorXd weights = metric_weights(*serial.problem);
  ProblemSetup split;
  split.problem = std::make_unique<DistributedProblem>(scaled);
  const std::shared_ptr<const AmbientSpace> space = split.problem->space();
  split.start = weights.cwiseProduct(serial.start).segment(space->first_row(), space->local_rows());
  split.domain = scale_domain(serial.domain, weights).distributed(space);
  split.suggested_step = serial.suggested_step;
  return split;
}

/// A covering on split states (in y) against one process's (in x): the same vertices and
/// triangles, the vertices within 1e-7, the same refinement and work, and valid.
inline void expect_same_covering(const CoveringResult& result, const CoveringResult& expected,
                                 const Eigen::VectorXd& weights) {
  const AmbientSpace& space = result.mesh.space();
  EXPECT_TRUE(space.is_distributed());
  EXPECT_EQ(result.mesh.ambient_dimension(), space.local_rows());
  ASSERT_EQ(result.mesh.vertex_count(), expected.mesh.vertex_count());
  EXPECT_EQ(result.mesh.triangles(), expected.mesh.triangles());
  double largest_gap = 0.0;
  for (int v = 0; v < result.mesh.vertex_count(); ++v) {
    const Eigen::VectorXd gap =
        result.mesh.point(v) -
        weights.cwiseProduct(expected.mesh.point(v)).segment(space.first_row(), space.local_rows());
    largest_gap = std::max(largest_gap, space.norm(gap));
  }
  EXPECT_LE(largest_gap, 1e-7);
  EXPECT_EQ(result.summary.refined_edges, expected.summary.refined_edges);
  EXPECT_EQ(result.summary.notes, expected.summary.notes);
  EXPECT_EQ(result.summary.factorisations, expected.summary.factorisations);
  EXPECT_EQ(result.summary.jacobian_evaluations, expected.summary.jacobian_evaluations);
  EXPECT_EQ(result.summary.function_evaluations, expected.summary.function_evaluations);
  ASSERT_TRUE(result.validation.has_value());
  EXPECT_TRUE(result.validation->is_valid()) << result.validation->report();
}

}  // namespace tessera::petsc
