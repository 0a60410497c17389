// SPDX-License-Identifier: MIT
// The PETSc backend against the serial one: the same problem (residual, Jacobian), the same
// tangent plane and solves, on whatever number of ranks mpiexec started. The correctors on a
// distributed problem: distributed_problem_test.cpp.
#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>

#include "tessera/core/error.h"
#include "tessera/core/scaled_problem.h"
#include "tessera/petsc/petsc_bratu.h"
#include "tessera/core/ambient_space.h"
#include "tessera/core/corrector.h"
#include "tessera/petsc/distributed_problem.h"
#include "tessera/petsc/petsc_linearization.h"
#include "tessera/problems/examples.h"

namespace tessera::petsc {
namespace {

// A deterministic vector with entries in [-1, 1], the same on every rank.
Eigen::VectorXd wobble(Eigen::Index n, double phase) {
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) {
    v(i) = std::sin(1.7 * static_cast<double>(i) + phase);
  }
  return v;
}

Owned<Vec> to_petsc(const PetscProblem& problem, const Eigen::VectorXd& values) {
  Owned<Vec> v = problem.create_vector();
  scatter(values, v);
  return v;
}

// The orthogonal projector onto the span of T's columns.
Eigen::MatrixXd projector(const Eigen::MatrixXd& T) {
  const Eigen::MatrixXd Q = T.householderQr().householderQ() * Eigen::MatrixXd::Identity(T.rows(), 2);
  return Q * Q.transpose();
}

// The 1-D (N = 40) and 2-D (N = 6) problems of both backends, and a point of M on the S-shaped
// branch (max u = 2, ε = 0.1): away from the folds, where (λ, ε) parametrise M.
struct Pair {
  std::unique_ptr<ImplicitProblem> serial;
  std::unique_ptr<PetscArrheniusBratu> distributed;
  Eigen::VectorXd on_M;
};

Pair make_pair(int dimension) {
  Pair pair;
  if (dimension == 1) {
    auto serial = std::make_unique<ArrheniusBratu>(40);
    pair.on_M = serial->point_with_amplitude(2.0, 0.1);
    pair.serial = std::move(serial);
  } else {
    auto serial = std::make_unique<ArrheniusBratu2D>(6);
    pair.on_M = serial->point_with_amplitude(2.0, 0.1);
    pair.serial = std::move(serial);
  }
  pair.distributed = std::make_unique<PetscArrheniusBratu>(
      PETSC_COMM_WORLD, dimension, dimension == 1 ? 40 : 6);
  return pair;
}

class Backend : public testing::TestWithParam<int> {};

TEST_P(Backend, ResidualAndJacobianAreTheSerialProblemsEntryByEntry) {
  const Pair pair = make_pair(GetParam());
  const int n = pair.serial->ambient_dimension();
  ASSERT_EQ(pair.distributed->ambient_dimension(), n);
  const Eigen::VectorXd x = pair.on_M + 0.3 * wobble(n, 0.4);
  Eigen::VectorXd F_serial(n - 2);
  pair.serial->evaluate(x, F_serial);
  Eigen::SparseMatrix<double> J_serial;
  pair.serial->sparse_jacobian(x, J_serial);

  Owned<Vec> xv = to_petsc(*pair.distributed, x);
  Owned<Vec> F = pair.distributed->create_vector();
  pair.distributed->evaluate(xv, F);
  const Eigen::VectorXd F_all = gather(F);
  EXPECT_LE((F_all.head(n - 2) - F_serial).norm(), 1e-13 * (1.0 + F_serial.norm()));
  EXPECT_EQ(F_all(n - 2), 0.0);
  EXPECT_EQ(F_all(n - 1), 0.0);

  Owned<Mat> J = pair.distributed->create_jacobian();
  pair.distributed->jacobian(xv, J);
  const Eigen::VectorXd v = wobble(n, 1.1);
  Owned<Vec> vv = to_petsc(*pair.distributed, v);
  Owned<Vec> Jv = pair.distributed->create_vector();
  ASSERT_EQ(MatMult(J, vv, Jv), 0);
  const Eigen::VectorXd Jv_all = gather(Jv);
  const Eigen::VectorXd expected = J_serial * v;
  EXPECT_LE((Jv_all.head(n - 2) - expected).norm(), 1e-13 * (1.0 + expected.norm()));
  EXPECT_EQ(pair.distributed->counts().function_evaluations, 1);
  EXPECT_EQ(pair.distributed->counts().jacobian_evaluations, 1);
}

TEST_P(Backend, TangentBasisIsOrthonormalAndSpansTheSerialTangentPlane) {
  const Pair pair = make_pair(GetParam());
  Owned<Vec> x = to_petsc(*pair.distributed, pair.on_M);
  DistributedLinearization linearization(*pair.distributed);
  ASSERT_TRUE(linearization.factor(x)) << linearization.last_failure();
  EXPECT_EQ(linearization.factorisations(), 1);
  Eigen::MatrixXd T(pair.on_M.size(), 2);
  T.col(0) = gather(linearization.tangent_basis()[0]);
  T.col(1) = gather(linearization.tangent_basis()[1]);
  EXPECT_LE((T.transpose() * T - Eigen::Matrix2d::Identity()).norm(), 1e-12);

  Linearization serial;
  ASSERT_TRUE(serial.factor(*pair.serial, pair.on_M));
  EXPECT_LE((projector(T) - projector(serial.tangent_basis())).norm(), 1e-9);
}

TEST_P(Backend, MinimumNormSolveSolvesTheSystemAndIsNormalToM) {
  const Pair pair = make_pair(GetParam());
  const int n = pair.serial->ambient_dimension();
  Owned<Vec> x = to_petsc(*pair.distributed, pair.on_M);
  DistributedLinearization linearization(*pair.distributed);
  ASSERT_TRUE(linearization.factor(x)) << linearization.last_failure();
  Eigen::VectorXd r = Eigen::VectorXd::Zero(n);
  r.head(n - 2) = wobble(n - 2, 0.7);
  Owned<Vec> rv = to_petsc(*pair.distributed, r);
  Owned<Vec> dx = pair.distributed->create_vector();
  linearization.solve_minimum_norm(rv, dx);
  const Eigen::VectorXd d = gather(dx);

  Eigen::SparseMatrix<double> J;
  pair.serial->sparse_jacobian(pair.on_M, J);
  EXPECT_LE((J * d - r.head(n - 2)).norm(), 1e-10 * r.norm());
  const Eigen::VectorXd t0 = gather(linearization.tangent_basis()[0]);
  const Eigen::VectorXd t1 = gather(linearization.tangent_basis()[1]);
  EXPECT_LE(std::abs(t0.dot(d)) + std::abs(t1.dot(d)), 1e-10 * d.norm());
}

TEST_P(Backend, ScaledProblemIsTheSerialScaledProblem) {
  const Pair pair = make_pair(GetParam());
  const int n = pair.serial->ambient_dimension();
  const ScaledProblem serial(*pair.serial, metric_weights(*pair.serial));
  const ScaledPetscProblem distributed(*pair.distributed);
  const Eigen::VectorXd y = serial.to_scaled(pair.on_M) + 0.01 * wobble(n, 0.3);
  Eigen::VectorXd F_serial(n - 2);
  serial.evaluate(y, F_serial);
  Owned<Vec> yv = to_petsc(distributed, y);
  Owned<Vec> F = distributed.create_vector();
  distributed.evaluate(yv, F);
  EXPECT_LE((gather(F).head(n - 2) - F_serial).norm(), 1e-13 * (1.0 + F_serial.norm()));

  Owned<Vec> x = to_petsc(distributed, pair.on_M);
  distributed.to_scaled(x);
  EXPECT_LE((gather(x) - serial.to_scaled(pair.on_M)).norm(), 1e-14 * pair.on_M.norm());
  // Projected by tessera's own corrector on the local rows: the serial scaled problem's point.
  const DistributedProblem adapter(distributed);
  const AmbientSpace& space = *adapter.space();
  Eigen::VectorXd local = y.segment(space.first_row(), space.local_rows());
  Linearization workspace;
  ASSERT_TRUE(tessera::project_gauss_newton(adapter, local, CorrectorOptions{}, workspace).is_success());
  Eigen::VectorXd serial_y = y;
  Linearization serial_workspace;
  ASSERT_TRUE(tessera::project_gauss_newton(serial, serial_y, CorrectorOptions{}, serial_workspace)
                  .is_success());
  EXPECT_LE((local - serial_y.segment(space.first_row(), space.local_rows())).norm(),
            1e-9 * (1.0 + serial_y.norm()));
}

INSTANTIATE_TEST_SUITE_P(Bratu, Backend, testing::Values(1, 2),
                         [](const testing::TestParamInfo<int>& info) {
                           return info.param == 1 ? std::string("OneDimensional")
                                                  : std::string("TwoDimensional");
                         });

TEST(PetscBratu, RefusesADimensionOrGridItCannotHold) {
  EXPECT_THROW(PetscArrheniusBratu(PETSC_COMM_WORLD, 3, 10), InvalidArgument);
  EXPECT_THROW(PetscArrheniusBratu(PETSC_COMM_WORLD, 2, 0), InvalidArgument);
  EXPECT_THROW(PetscArrheniusBratu(PETSC_COMM_WORLD, 2, 20000), InvalidArgument);
}

TEST(PetscBratu, ErrorsOfPetscBecomeExceptionsNamingTheCall) {
  try {
    check(PETSC_ERR_ARG_OUTOFRANGE, "VecSetValue");
    FAIL() << "no exception";
  } catch (const ComputationFailed& error) {
    EXPECT_NE(std::string(error.what()).find("VecSetValue"), std::string::npos) << error.what();
  }
}

}  // namespace
}  // namespace tessera::petsc
