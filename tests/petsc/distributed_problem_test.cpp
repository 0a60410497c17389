// SPDX-License-Identifier: MIT
// tessera's own correctors (core/corrector.h), unchanged, on the local rows of a distributed
// problem: the SPMD design of the PETSc backend (docs/cluster.md). Every rank runs the same
// code on its rows; reductions go through DistributedSpace, factorisations through PETSc.
#include <gtest/gtest.h>

#include <cmath>

#include "tessera/core/corrector.h"
#include "tessera/core/counted_problem.h"
#include "tessera/core/error.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/problems/examples.h"

namespace tessera::petsc {
namespace {

Eigen::VectorXd wobble(Eigen::Index n, double phase) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    v(i) = std::sin(1.3 * static_cast<double>(i) + phase);
  }
  return v;
}

TEST(DistributedSpace, SumsAreTheSameBitsOnEveryRankAndMatchOneProcess) {
  PetscArrheniusBratu problem(PETSC_COMM_WORLD, 2, 9);
  const DistributedProblem distributed(problem);
  const AmbientSpace& space = *distributed.space();
  const int n = space.dimension();
  const Eigen::VectorXd a = wobble(n, 0.1);
  const Eigen::VectorXd b = wobble(n, 0.9);
  const auto local = [&](const Eigen::VectorXd& v) {
    return Eigen::VectorXd(v.segment(space.first_row(), space.local_rows()));
  };
  const double dot = space.dot(local(a), local(b));
  EXPECT_NEAR(dot, a.dot(b), 1e-12 * a.norm() * b.norm());
  // The same bits everywhere: the largest and smallest over the ranks agree exactly.
  EXPECT_EQ(space.maximum(dot), -space.maximum(-dot));
  EXPECT_EQ(space.coordinate(local(a), n - 1), a(n - 1));
  Eigen::MatrixXd T(space.local_rows(), 2);
  T << local(a), local(b);
  EXPECT_LE((space.products(T, T) - Eigen::Matrix2d{{a.dot(a), a.dot(b)}, {a.dot(b), b.dot(b)}})
                .norm(),
            1e-12 * a.squaredNorm());
}

class Corrector : public testing::TestWithParam<int> {};

TEST_P(Corrector, TheSerialCorrectorsRunOnTheLocalRowsAndLandWhereTheyLandInOneProcess) {
  const int dimension = GetParam();
  std::unique_ptr<ImplicitProblem> serial_problem;
  Eigen::VectorXd on_M;
  if (dimension == 1) {
    auto bvp = std::make_unique<ArrheniusBratu>(40);
    on_M = bvp->point_with_amplitude(3.0, 0.1);
    serial_problem = std::move(bvp);
  } else {
    auto bratu2d = std::make_unique<ArrheniusBratu2D>(7);
    on_M = bratu2d->point_with_amplitude(3.0, 0.1);
    serial_problem = std::move(bratu2d);
  }
  const ImplicitProblem& serial = *serial_problem;
  const int n = serial.ambient_dimension();
  const Eigen::VectorXd start = on_M + 0.05 * wobble(n, 0.5);

  Eigen::VectorXd serial_x = start;
  Linearization serial_workspace;
  const CorrectorSummary serial_summary =
      project_gauss_newton(serial, serial_x, CorrectorOptions{}, serial_workspace);
  ASSERT_TRUE(serial_summary.is_success());

  PetscArrheniusBratu petsc_problem(PETSC_COMM_WORLD, dimension, dimension == 1 ? 40 : 7);
  const DistributedProblem distributed(petsc_problem);
  const CountedProblem counted(distributed);
  const AmbientSpace& space = *distributed.space();
  Eigen::VectorXd x = start.segment(space.first_row(), space.local_rows());
  Linearization workspace;
  const CorrectorSummary summary = project_gauss_newton(counted, x, CorrectorOptions{}, workspace);
  ASSERT_TRUE(summary.is_success()) << summary.brief_report();
  EXPECT_LE((x - serial_x.segment(space.first_row(), space.local_rows())).norm(),
            1e-9 * serial_x.norm());
  EXPECT_EQ(summary.iterations, serial_summary.iterations);
  EXPECT_EQ(counted.factorisations(), summary.iterations);
  EXPECT_EQ(counted.jacobian_evaluations(), summary.iterations);
  EXPECT_EQ(workspace.tangent_basis().rows(), space.local_rows());
  EXPECT_NEAR(space.squared_norm(workspace.tangent_basis().col(0)), 1.0, 1e-12);

  // A chord from that factorisation keeps the predictor's tangent coordinates.
  const Eigen::MatrixXd& T = workspace.tangent_basis();
  Eigen::VectorXd y = x + 0.2 * T.col(0) + 0.1 * T.col(1);
  ASSERT_TRUE(project_chord(counted, workspace, y, CorrectorOptions{}).is_success());
  const Eigen::Vector2d along = space.tangent_coordinates(T, y - x);
  EXPECT_NEAR(along(0), 0.2, 1e-9);
  EXPECT_NEAR(along(1), 0.1, 1e-9);
  const double bound = chord_distance_bound(counted, workspace, x + 0.2 * T.col(0), 1e-6,
                                            CorrectorOptions{});
  EXPECT_GT(bound, 0.0);
  EXPECT_LT(bound, 0.2);
}

INSTANTIATE_TEST_SUITE_P(Bratu, Corrector, testing::Values(1, 2),
                         [](const testing::TestParamInfo<int>& info) {
                           return info.param == 1 ? std::string("OneDimensional")
                                                  : std::string("TwoDimensional");
                         });

TEST(DistributedProblem, RefusesWhatNeedsAnEigenJacobianOrSerialScaling) {
  PetscArrheniusBratu petsc_problem(PETSC_COMM_WORLD, 1, 20);
  const DistributedProblem distributed(petsc_problem);
  Eigen::SparseMatrix<double> J;
  EXPECT_THROW(distributed.sparse_jacobian(Eigen::VectorXd::Zero(distributed.space()->local_rows()), J),
               InvalidArgument);
  EXPECT_THROW(ScaledProblem(distributed, Eigen::VectorXd::Ones(22)), InvalidArgument);
}

}  // namespace
}  // namespace tessera::petsc
