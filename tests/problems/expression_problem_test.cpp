// SPDX-License-Identifier: MIT
#include "tessera/problems/expression_problem.h"

#include <gtest/gtest.h>

// Defined with the counting allocator in expression_test.cpp.
long tessera_test_allocation_count();

namespace {

using tessera::Expression;
using tessera::ExpressionProblem;
using tessera::InvalidArgument;

const std::vector<std::string> xyzw = {"x", "y", "z", "w"};

// Two cylinders x² + y² = 1 and z² + w² = 1 in R^4: the flat torus.
ExpressionProblem flat_torus() {
  return ExpressionProblem("flat_torus",
                           {Expression("x^2 + y^2 - 1", xyzw), Expression("z^2 + w^2 - 1", xyzw)});
}

TEST(ExpressionProblem, EvaluatesFAndTheExactJacobian) {
  const ExpressionProblem problem = flat_torus();
  EXPECT_EQ(problem.ambient_dimension(), 4);
  EXPECT_EQ(problem.equation_count(), 2);
  EXPECT_EQ(problem.name(), "flat_torus");
  EXPECT_EQ(problem.coordinate_names(), xyzw);
  const Eigen::Vector4d x(0.5, 2.0, -1.0, 3.0);
  Eigen::Vector2d F;
  problem.evaluate(x, F);
  EXPECT_EQ(F, Eigen::Vector2d(0.25 + 4.0 - 1.0, 1.0 + 9.0 - 1.0));
  Eigen::MatrixXd J(2, 4);
  problem.jacobian(x, J);
  Eigen::MatrixXd expected(2, 4);
  expected << 1.0, 4.0, 0.0, 0.0,  //
      0.0, 0.0, -2.0, 6.0;
  EXPECT_EQ(J, expected);
}

TEST(ExpressionProblem, SparseJacobianIsTheDenseOne) {
  const ExpressionProblem problem = flat_torus();
  const Eigen::Vector4d x(0.5, 2.0, -1.0, 3.0);
  Eigen::SparseMatrix<double> sparse;
  problem.sparse_jacobian(x, sparse);
  Eigen::MatrixXd dense(2, 4);
  problem.jacobian(x, dense);
  EXPECT_EQ(Eigen::MatrixXd(sparse), dense);
}

TEST(ExpressionProblem, EvaluationDoesNotAllocateAfterTheFirstCall) {
  const ExpressionProblem problem = flat_torus();
  const Eigen::Vector4d x(0.5, 2.0, -1.0, 3.0);
  Eigen::Vector2d F;
  Eigen::Matrix<double, 2, 4> J;
  problem.jacobian(x, J);
  const long before = tessera_test_allocation_count();
  for (int i = 0; i < 50; ++i) {
    problem.evaluate(x, F);
    problem.jacobian(x, J);
  }
  EXPECT_EQ(tessera_test_allocation_count() - before, 0);
}

TEST(ExpressionProblem, RejectsInconsistentEquations) {
  EXPECT_THROW(ExpressionProblem("none", {}), InvalidArgument);
  // Two variables: a curve at best, not a 2-manifold.
  EXPECT_THROW(ExpressionProblem("plane", {Expression("x + y", {"x", "y"})}), InvalidArgument);
  // Four variables need two equations.
  EXPECT_THROW(ExpressionProblem("short", {Expression("x", xyzw)}), InvalidArgument);
  EXPECT_THROW(
      ExpressionProblem("mixed", {Expression("x", xyzw), Expression("x", {"x", "y", "z", "v"})}),
      InvalidArgument);
  try {
    ExpressionProblem("short", {Expression("x", xyzw)});
  } catch (const InvalidArgument& error) {
    EXPECT_NE(std::string(error.what()).find("4 variables need n-2 = 2 equations, found 1"),
              std::string::npos)
        << error.what();
  }
}

TEST(ExpressionProblem, ChecksShapes) {
  const ExpressionProblem problem = flat_torus();
  Eigen::VectorXd F(3);
  EXPECT_THROW(problem.evaluate(Eigen::Vector4d::Zero(), F), InvalidArgument);
  Eigen::MatrixXd J(2, 3);
  EXPECT_THROW(problem.jacobian(Eigen::Vector4d::Zero(), J), InvalidArgument);
}

}  // namespace
