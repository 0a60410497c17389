// SPDX-License-Identifier: MIT
// The two-dimensional Arrhenius–Bratu problem (ArrheniusBratu2D) and its catalogue entry
// `bratu2d`: exact Jacobian, points on M, the metric's block, the fold structure, parameters.
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <set>
#include <string>

#include "support/test_support.h"
#include "tessera/core/error.h"
#include "tessera/problems/catalogue.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

Eigen::VectorXd residual(const ImplicitProblem& problem, const Eigen::VectorXd& x) {
  Eigen::VectorXd F(problem.equation_count());
  problem.evaluate(x, F);
  return F;
}

// A point off M: u_ij ∈ [0, 3], λ ∈ [1, 8], ε ∈ [0, 0.3].
Eigen::VectorXd random_point(int N, unsigned seed) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  Eigen::VectorXd x(N * N + 2);
  for (int i = 0; i < N * N; ++i) {
    x(i) = 3.0 * uniform(generator);
  }
  x(N * N) = 1.0 + 7.0 * uniform(generator);
  x(N * N + 1) = 0.3 * uniform(generator);
  return x;
}

// Central differences with step δ = 1e-6·max(1, |x_j|): truncation δ²/6·|∂³F| ≲ 1e-12·e³·h²λ and
// rounding 1e-16·|F|/δ ≲ 1e-9 at these points, far below the tolerance 1e-7 on entries of O(1).
TEST(ArrheniusBratu2D, JacobianMatchesCentralDifferencesAtARandomPoint) {
  for (const int N : {1, 2, 5}) {
    SCOPED_TRACE(N);
    const ArrheniusBratu2D problem(N);
    const Eigen::VectorXd x = random_point(N, 11 + N);
    Eigen::MatrixXd J(problem.equation_count(), problem.ambient_dimension());
    problem.jacobian(x, J);
    Eigen::MatrixXd difference_quotient(J.rows(), J.cols());
    for (Eigen::Index j = 0; j < x.size(); ++j) {
      const double delta = 1e-6 * std::max(1.0, std::abs(x(j)));
      Eigen::VectorXd forward = x, backward = x;
      forward(j) += delta;
      backward(j) -= delta;
      difference_quotient.col(j) =
          (residual(problem, forward) - residual(problem, backward)) / (2.0 * delta);
    }
    EXPECT_LE((J - difference_quotient).cwiseAbs().maxCoeff(), 1e-7);
  }
}

TEST(ArrheniusBratu2D, SparseJacobianIsTheFivePointStencilPlusTwoColumnsAndReusesStorage) {
  const int N = 6;
  const ArrheniusBratu2D problem(N);
  const Eigen::VectorXd x = random_point(N, 3);
  Eigen::SparseMatrix<double> J;
  problem.sparse_jacobian(x, J);
  EXPECT_EQ(J.rows(), N * N);
  EXPECT_EQ(J.cols(), N * N + 2);
  EXPECT_EQ(J.nonZeros(), 7 * N * N - 4 * N);
  EXPECT_TRUE(J.isCompressed());
  // The stencil couples u_ij only with its four neighbours, each with coefficient 1.
  EXPECT_EQ(J.coeff(7, 8), 1.0);   // (2, 2) and (2, 3): same row of the grid
  EXPECT_EQ(J.coeff(7, 13), 1.0);  // (2, 2) and (3, 2): same column
  EXPECT_EQ(J.coeff(5, 6), 0.0);   // (1, 6) and (2, 1): adjacent indices, not neighbours
  const double* values = J.valuePtr();
  const int* inner = J.innerIndexPtr();
  problem.sparse_jacobian(x + Eigen::VectorXd::Constant(x.size(), 0.01), J);
  EXPECT_EQ(J.valuePtr(), values) << "second call reallocated the values";
  EXPECT_EQ(J.innerIndexPtr(), inner) << "second call reallocated the row indices";
}

// The grid's symmetries (the square's dihedral group) map solutions to solutions; the ones that
// point_with_amplitude reaches are symmetric and largest at the centre.
void expect_symmetric_with_maximum_at_centre(const Eigen::VectorXd& x, int N, double amplitude) {
  const auto u = [&](int row, int column) { return x(row * N + column); };
  for (int row = 0; row < N; ++row) {
    for (int column = 0; column < N; ++column) {
      EXPECT_NEAR(u(row, column), u(column, row), 1e-9);
      EXPECT_NEAR(u(row, column), u(N - 1 - row, column), 1e-9);
      EXPECT_NEAR(u(row, column), u(row, N - 1 - column), 1e-9);
      EXPECT_LE(u(row, column), amplitude + 1e-12);
      EXPECT_GT(u(row, column), 0.0);
    }
  }
}

TEST(ArrheniusBratu2D, PointWithAmplitudeLiesOnMWithTheRequestedCentreValue) {
  for (const int N : {11, 12}) {  // the centre is a grid point (odd N) or four of them (even N)
    for (const auto& [amplitude, epsilon] :
         std::vector<std::pair<double, double>>{{0.7, 0.0}, {6.0, 0.2}, {12.0, 0.3}}) {
      SCOPED_TRACE(::testing::Message()
                   << "N = " << N << ", amplitude " << amplitude << ", epsilon " << epsilon);
      const ArrheniusBratu2D problem(N);
      const Eigen::VectorXd x = problem.point_with_amplitude(amplitude, epsilon);
      ASSERT_EQ(x.size(), N * N + 2);
      EXPECT_LE(residual(problem, x).lpNorm<Eigen::Infinity>(), 1e-10);
      EXPECT_NEAR(x(problem.centre_index()), amplitude, 1e-12);
      EXPECT_EQ(x(N * N + 1), epsilon);
      EXPECT_GT(x(N * N), 0.0);
      expect_symmetric_with_maximum_at_centre(x, N, amplitude);
    }
  }
  const ArrheniusBratu2D problem(4);
  EXPECT_EQ(residual(problem, problem.point_with_amplitude(0.0, 0.1)).norm(), 0.0);
  EXPECT_THROW(problem.point_with_amplitude(-1.0, 0.1), InvalidArgument);
  EXPECT_THROW(problem.point_with_amplitude(1.0, -0.1), InvalidArgument);
}

// The five-point Laplacian is second order: at a fixed centre value, λ_N converges like h², so
// successive differences shrink by 4 as h halves (odd N keeps the centre on the grid).
TEST(ArrheniusBratu2D, LambdaConvergesWithOrderTwo) {
  std::vector<double> lambda, h;
  for (const int N : {15, 31, 63, 127}) {
    lambda.push_back(ArrheniusBratu2D(N).point_with_amplitude(1.0, 0.0)(N * N));
    h.push_back(1.0 / (N + 1));
  }
  const std::vector<double> differences = {std::abs(lambda[1] - lambda[0]),
                                           std::abs(lambda[2] - lambda[1]),
                                           std::abs(lambda[3] - lambda[2])};
  EXPECT_NEAR(testing::observed_order({h[0], h[1], h[2]}, differences), 2.0, 0.1);
}

// ε = 0: Gelfand's problem on the square has one fold, λ* ≈ 6.808 (continuous problem) at
// u_c ≈ 1.39; ε = 0.2 is S-shaped (folds near u_c = 2.9 and 18), ε = 0.3 beyond the cusp.
TEST(ArrheniusBratu2D, FoldStructure) {
  const int N = 15;
  const ArrheniusBratu2D problem(N);
  const auto lambda = [&](double amplitude, double epsilon) {
    return problem.point_with_amplitude(amplitude, epsilon)(N * N);
  };
  const double fold = lambda(1.389, 0.0);
  EXPECT_NEAR(fold, 6.80, 0.02);  // N = 15: 6.8022; the continuous value is 6.808
  EXPECT_GT(fold, lambda(1.2, 0.0));
  EXPECT_GT(fold, lambda(1.6, 0.0));
  EXPECT_GT(lambda(2.9, 0.2), lambda(10.0, 0.2));
  EXPECT_GT(lambda(10.0, 0.2), lambda(18.2, 0.2));
  EXPECT_LT(lambda(18.2, 0.2), lambda(20.0, 0.2));
  double previous = 0.0;
  for (double amplitude = 1.0; amplitude <= 20.0; amplitude += 1.0) {
    const double current = lambda(amplitude, 0.3);
    EXPECT_GT(current, previous) << "ε = 0.3 is above the cusp: λ increases with u_c";
    previous = current;
  }
}

TEST(ArrheniusBratu2D, NamesAndTheWeightedBlockOfGridValues) {
  const int N = 3;
  const ArrheniusBratu2D problem(N);
  const auto names = problem.coordinate_names();
  ASSERT_EQ(static_cast<int>(names.size()), N * N + 2);
  EXPECT_EQ(names[0], "u_1_1");
  EXPECT_EQ(names[1], "u_1_2");
  EXPECT_EQ(names[3], "u_2_1");
  EXPECT_EQ(names[N * N - 1], "u_3_3");
  EXPECT_EQ(names[N * N], "lambda");
  EXPECT_EQ(names[N * N + 1], "epsilon");
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
  EXPECT_EQ(problem.centre_index(), 4);              // u_2_2
  EXPECT_EQ(ArrheniusBratu2D(4).centre_index(), 5);  // u_2_2 of four equal central values

  const auto blocks = problem.coordinate_blocks();
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].name, "u");
  EXPECT_EQ(blocks[0].first, 0);
  EXPECT_EQ(blocks[0].size, N * N);
  EXPECT_DOUBLE_EQ(blocks[0].weight, 0.25);  // h = 1/(N + 1)
  // h‖u‖ approximates the L² norm on the square: for u = 1 it is (h² N²)^½ = N h → 1.
  const Eigen::VectorXd weights = metric_weights(problem);
  ASSERT_EQ(weights.size(), N * N + 2);
  EXPECT_DOUBLE_EQ(weights(0), 0.25);
  EXPECT_DOUBLE_EQ(weights(N * N - 1), 0.25);
  EXPECT_EQ(weights(N * N), 1.0);
  EXPECT_EQ(weights(N * N + 1), 1.0);
}

TEST(Bratu2dCatalogueEntry, BuildsASetupOnMInsideItsDomain) {
  const ProblemSetup setup = make_catalogue_problem("bratu2d:N=8");
  const int n = 8 * 8 + 2;
  ASSERT_EQ(setup.problem->ambient_dimension(), n);
  EXPECT_EQ(setup.problem->name(), "bratu2d");
  EXPECT_EQ(setup.start.size(), n);
  EXPECT_LT(residual(*setup.problem, setup.start).lpNorm<Eigen::Infinity>(), 1e-12);
  EXPECT_EQ(setup.domain.half_spaces().size(), 5u);  // λ, ε, u_c bounds: O(1) faces, not O(N²)
  EXPECT_GT(setup.domain.boundary_distance(setup.start).signed_distance, 0.0);
  EXPECT_NEAR(setup.start(dynamic_cast<const ArrheniusBratu2D&>(*setup.problem).centre_index()),
              6.0, 1e-12);
  EXPECT_EQ(setup.start(n - 1), 0.2);
  EXPECT_TRUE(setup.problem->has_sparse_jacobian());
  EXPECT_EQ(setup.description.rfind("bratu2d N=8:", 0), 0u) << setup.description;
  EXPECT_EQ(setup.expected_euler_characteristic, 1);
  // The step is a length in the weighted metric, independent of N.
  EXPECT_EQ(make_catalogue_problem("bratu2d:N=4").suggested_step, setup.suggested_step);
}

TEST(Bratu2dCatalogueEntry, TheDefaultGridBuildsWithASparseJacobian) {
  const ProblemSetup setup = make_catalogue_problem("bratu2d");
  const int N = 32;
  EXPECT_EQ(setup.problem->ambient_dimension(), N * N + 2);
  EXPECT_LT(residual(*setup.problem, setup.start).lpNorm<Eigen::Infinity>(), 1e-12);
  Eigen::SparseMatrix<double> J;
  setup.problem->sparse_jacobian(setup.start, J);
  EXPECT_EQ(J.nonZeros(), 7 * N * N - 4 * N);
}

void expect_invalid(const std::string& specification, const std::vector<std::string>& fragments) {
  try {
    make_catalogue_problem(specification);
    ADD_FAILURE() << "no exception for '" << specification << "'";
  } catch (const InvalidArgument& e) {
    for (const std::string& fragment : fragments) {
      EXPECT_NE(std::string(e.what()).find(fragment), std::string::npos)
          << "'" << specification << "': " << e.what();
    }
  }
}

TEST(Bratu2dCatalogueEntry, RejectsBadGridSizesWithActionableMessages) {
  expect_invalid("bratu2d:N=0", {"bratu2d N = 0", "whole number in [1, 1000]"});
  expect_invalid("bratu2d:N=-3", {"N = -3"});
  expect_invalid("bratu2d:N=2.5", {"N = 2.5", "whole number"});
  expect_invalid("bratu2d:N=1e6", {"N = 1e+06", "[1, 1000]"});
  expect_invalid("bratu2d:points=10", {"no parameter 'points'", "N"});
  EXPECT_THROW(ArrheniusBratu2D(0), InvalidArgument);
  EXPECT_THROW(ArrheniusBratu2D(1001), InvalidArgument);
}

}  // namespace
}  // namespace tessera
