// SPDX-License-Identifier: MIT
// Every sparse LU solver of the build against a dense LU, on bordered systems shaped like
// tessera's: a discrete 2-D operator, two dense parameter columns, two coordinate rows.
#include "tessera/core/sparse_lu.h"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <random>
#include <string>
#include <vector>

#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

// J: (k²)×(k²+2), a five-point convection–diffusion stencil on a k×k grid (unsymmetric, so that
// pivoting matters) with diagonal shift `shift`, and two dense columns; bordered with the
// coordinate rows of the two parameters, A = [J; e_{n−2}ᵀ; e_{n−1}ᵀ] is n×n, n = k² + 2.
Eigen::SparseMatrix<double> bordered_test_matrix(int k, double shift, unsigned seed) {
  const int m = k * k;
  const int n = m + 2;
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int row = 0; row < k; ++row) {
    for (int column = 0; column < k; ++column) {
      const int i = row * k + column;
      entries.emplace_back(i, i, -4.0 + shift + 0.1 * uniform(generator));
      if (column > 0) {
        entries.emplace_back(i, i - 1, 1.3);
      }
      if (column + 1 < k) {
        entries.emplace_back(i, i + 1, 0.7);
      }
      if (row > 0) {
        entries.emplace_back(i, i - k, 1.0);
      }
      if (row + 1 < k) {
        entries.emplace_back(i, i + k, 1.0);
      }
      entries.emplace_back(i, m, uniform(generator));
      entries.emplace_back(i, m + 1, uniform(generator));
    }
  }
  Eigen::SparseMatrix<double> J(m, n);
  J.setFromTriplets(entries.begin(), entries.end());
  Eigen::SparseMatrix<double> A;
  bordered_jacobian(J, {{n - 2, m / 2, 1.0}, {n - 1, m + 1, 1.0}}, A);
  return A;
}

Eigen::MatrixXd random_matrix(Eigen::Index rows, Eigen::Index columns, unsigned seed) {
  std::mt19937 generator(seed);
  std::normal_distribution<double> normal;
  Eigen::MatrixXd M(rows, columns);
  for (Eigen::Index j = 0; j < columns; ++j) {
    for (Eigen::Index i = 0; i < rows; ++i) {
      M(i, j) = normal(generator);
    }
  }
  return M;
}

// ‖X − A⁻¹B‖/‖A⁻¹B‖ against Eigen's dense partial-pivoting LU. These matrices have condition
// numbers below 1e4, so both sides are accurate to ~1e-12; 1e-10 leaves room.
double relative_error(const Eigen::SparseMatrix<double>& A, const Eigen::MatrixXd& B,
                      const Eigen::MatrixXd& X) {
  const Eigen::MatrixXd expected = Eigen::MatrixXd(A).partialPivLu().solve(B);
  return (X - expected).norm() / expected.norm();
}
constexpr double kAgreement = 1e-10;

class EverySparseLu : public ::testing::TestWithParam<SparseLuSolver> {};

TEST_P(EverySparseLu, SolvesABorderedSystemLikeADenseLu) {
  const Eigen::SparseMatrix<double> A = bordered_test_matrix(9, 0.0, 1);
  auto lu = make_sparse_lu(GetParam());
  EXPECT_EQ(lu->solver(), GetParam());
  ASSERT_EQ(lu->analyze(A), SparseLuStatus::Success) << lu->last_message();
  EXPECT_TRUE(lu->is_analyzed_for(A));
  EXPECT_FALSE(lu->is_factored());
  ASSERT_EQ(lu->factorize(A), SparseLuStatus::Success) << lu->last_message();
  EXPECT_TRUE(lu->is_factored());
  const Eigen::MatrixXd B = random_matrix(A.rows(), 3, 2);
  Eigen::MatrixXd X(A.rows(), 3);
  lu->solve(B, X);
  EXPECT_LT(relative_error(A, B, X), kAgreement);
  // In place: X may be B.
  Eigen::MatrixXd Y = B;
  lu->solve(Y, Y);
  EXPECT_LT((Y - X).norm(), 1e-14 * X.norm());
  // One column, a vector.
  Eigen::VectorXd y = B.col(1);
  lu->solve(y, y);
  EXPECT_LT((y - X.col(1)).norm(), 1e-14 * X.norm());
  // The factors hold at least A's diagonal: nnz(L) + nnz(U) ≥ n.
  const auto fill = lu->factor_nonzeros();
  ASSERT_TRUE(fill.has_value());
  EXPECT_GE(*fill, A.rows());
}

// New values on the analysed pattern, including values that reverse which entries dominate: a
// solver that reuses pivots (KLU's refactorisation) must notice and pivot again.
TEST_P(EverySparseLu, RefactorisesNewValuesOnTheSamePattern) {
  auto lu = make_sparse_lu(GetParam());
  const Eigen::SparseMatrix<double> first = bordered_test_matrix(8, 0.0, 3);
  ASSERT_EQ(lu->analyze(first), SparseLuStatus::Success);
  ASSERT_EQ(lu->factorize(first), SparseLuStatus::Success);
  const Eigen::MatrixXd B = random_matrix(first.rows(), 2, 4);
  for (const double shift : {0.01, 3.9, 8.0, -3.0}) {
    SCOPED_TRACE(shift);
    const Eigen::SparseMatrix<double> next = bordered_test_matrix(8, shift, 5);
    ASSERT_TRUE(lu->is_analyzed_for(next));
    ASSERT_EQ(lu->factorize(next), SparseLuStatus::Success) << lu->last_message();
    Eigen::MatrixXd X(B.rows(), B.cols());
    lu->solve(B, X);
    EXPECT_LT(relative_error(next, B, X), kAgreement);
  }
}

// Objects that analyse the same pattern (KLU shares one symbolic analysis among them): each
// factors and solves its own values, and outlives the others.
TEST_P(EverySparseLu, FactorisationsOfOnePatternAreIndependent) {
  const Eigen::SparseMatrix<double> A = bordered_test_matrix(8, 0.0, 6);
  const Eigen::SparseMatrix<double> C = bordered_test_matrix(8, 2.5, 7);
  auto first = make_sparse_lu(GetParam());
  auto second = make_sparse_lu(GetParam());
  ASSERT_EQ(first->analyze(A), SparseLuStatus::Success);
  ASSERT_EQ(first->factorize(A), SparseLuStatus::Success);
  ASSERT_EQ(second->analyze(C), SparseLuStatus::Success);
  ASSERT_EQ(second->factorize(C), SparseLuStatus::Success);
  const Eigen::MatrixXd B = random_matrix(A.rows(), 2, 8);
  Eigen::MatrixXd X(B.rows(), B.cols());
  first->solve(B, X);
  EXPECT_LT(relative_error(A, B, X), kAgreement);
  first.reset();
  auto third = make_sparse_lu(GetParam());  // a later analysis of the same pattern
  ASSERT_EQ(third->analyze(A), SparseLuStatus::Success);
  ASSERT_EQ(third->factorize(A), SparseLuStatus::Success);
  second->solve(B, X);
  EXPECT_LT(relative_error(C, B, X), kAgreement);
  third->solve(B, X);
  EXPECT_LT(relative_error(A, B, X), kAgreement);
}

TEST_P(EverySparseLu, ReportsASingularMatrixAsAValue) {
  // The border row e_{n−1}ᵀ repeated: rows n−2 and n−1 are equal, A is singular.
  Eigen::SparseMatrix<double> A = bordered_test_matrix(6, 0.0, 6);
  const int n = static_cast<int>(A.rows());
  Eigen::SparseMatrix<double> J = A.topRows(n - 2);
  bordered_jacobian(J, {{n - 2, n - 1, 1.0}, {n - 1, n - 1, 1.0}}, A);
  auto lu = make_sparse_lu(GetParam());
  ASSERT_EQ(lu->analyze(A), SparseLuStatus::Success);
  EXPECT_EQ(lu->factorize(A), SparseLuStatus::Singular);
  EXPECT_FALSE(lu->is_factored());
  EXPECT_FALSE(lu->last_message().empty());
  EXPECT_FALSE(lu->factor_nonzeros().has_value());
  Eigen::VectorXd x = Eigen::VectorXd::Ones(n);
  EXPECT_THROW(lu->solve(x, x), InvalidArgument);
  // A regular matrix afterwards is fine again.
  const Eigen::SparseMatrix<double> regular = bordered_test_matrix(6, 0.0, 6);
  ASSERT_EQ(lu->analyze(regular), SparseLuStatus::Success);
  EXPECT_EQ(lu->factorize(regular), SparseLuStatus::Success);
}

TEST_P(EverySparseLu, RefusesAPatternItDidNotAnalyse) {
  auto lu = make_sparse_lu(GetParam());
  const Eigen::SparseMatrix<double> A = bordered_test_matrix(5, 0.0, 7);
  EXPECT_FALSE(lu->is_analyzed_for(A));
  EXPECT_THROW(lu->factorize(A), InvalidArgument);
  ASSERT_EQ(lu->analyze(A), SparseLuStatus::Success);
  // The same values with the second border row moved: another pattern.
  const int n = static_cast<int>(A.rows());
  Eigen::SparseMatrix<double> J = A.topRows(n - 2);
  Eigen::SparseMatrix<double> moved;
  bordered_jacobian(J, {{n - 2, 3, 1.0}, {n - 1, n - 2, 1.0}}, moved);
  EXPECT_FALSE(lu->is_analyzed_for(moved));
  try {
    lu->factorize(moved);
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    EXPECT_NE(std::string(e.what()).find("was not analysed"), std::string::npos) << e.what();
  }
  Eigen::SparseMatrix<double> rectangular(4, 5);
  rectangular.makeCompressed();
  EXPECT_THROW(lu->analyze(rectangular), InvalidArgument);
  ASSERT_EQ(lu->factorize(A), SparseLuStatus::Success);
  Eigen::MatrixXd wrong_shape = Eigen::MatrixXd::Ones(n + 1, 1);
  EXPECT_THROW(lu->solve(wrong_shape, wrong_shape), InvalidArgument);
}

// Sets TESSERA_SPARSE_LU for the lifetime of the object and restores it afterwards.
class SolverEnvironment {
 public:
  explicit SolverEnvironment(std::string_view value) {
    if (const char* old = std::getenv("TESSERA_SPARSE_LU")) {
      saved_ = old;
    }
    setenv("TESSERA_SPARSE_LU", std::string(value).c_str(), 1);
  }
  ~SolverEnvironment() {
    if (saved_) {
      setenv("TESSERA_SPARSE_LU", saved_->c_str(), 1);
    } else {
      unsetenv("TESSERA_SPARSE_LU");
    }
  }
  SolverEnvironment(const SolverEnvironment&) = delete;
  SolverEnvironment& operator=(const SolverEnvironment&) = delete;

 private:
  std::optional<std::string> saved_;
};

// F(x) = K x + 0.1 sin(x)(componentwise on the first n−2 coordinates), K = [five-point stencil,
// two dense columns]: a 2-manifold through 0 with a sparse Jacobian, or the same with a dense one.
class SparseTestProblem final : public ImplicitProblem {
 public:
  SparseTestProblem(int k, bool sparse)
      : K_(bordered_test_matrix(k, 0.0, 8).topRows(k * k)), sparse_(sparse) {}
  int ambient_dimension() const override { return static_cast<int>(K_.cols()); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    F = K_ * x;
    F.array() += 0.1 * x.head(F.size()).array().sin();
  }
  bool has_sparse_jacobian() const override { return sparse_; }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    Eigen::SparseMatrix<double> sparse;
    sparse_jacobian(x, sparse);
    J = Eigen::MatrixXd(sparse);
  }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    J = K_;
    for (int i = 0; i < J.rows(); ++i) {
      J.coeffRef(i, i) += 0.1 * std::cos(x(i));
    }
    J.makeCompressed();
  }

 private:
  Eigen::SparseMatrix<double> K_;
  bool sparse_;
};

// The sparse linearisation with this solver (chosen by TESSERA_SPARSE_LU) gives the dense QR's
// tangent space and minimum-norm solution.
TEST_P(EverySparseLu, LinearizationAgreesWithTheDenseQr) {
  const SolverEnvironment environment(name(GetParam()));
  EXPECT_EQ(default_sparse_lu_solver(), GetParam());
  const SparseTestProblem sparse(7, true);
  const SparseTestProblem dense(7, false);
  const int n = sparse.ambient_dimension();
  const Eigen::VectorXd x = 0.01 * random_matrix(n, 1, 9);
  Linearization sparse_linearization;
  Linearization dense_linearization;
  ASSERT_TRUE(sparse_linearization.factor(sparse, x));
  ASSERT_TRUE(dense_linearization.factor(dense, x));
  const Eigen::MatrixXd& T = sparse_linearization.tangent_basis();
  const Eigen::MatrixXd& T_dense = dense_linearization.tangent_basis();
  // Same plane: the projector onto it agrees.
  EXPECT_LT((T * T.transpose() - T_dense * T_dense.transpose()).norm(), 1e-12);
  const Eigen::VectorXd rhs = random_matrix(n - 2, 1, 10);
  Eigen::VectorXd dx(n), dx_dense(n);
  sparse_linearization.solve_minimum_norm(rhs, dx);
  dense_linearization.solve_minimum_norm(rhs, dx_dense);
  EXPECT_LT((dx - dx_dense).norm(), 1e-11 * dx_dense.norm());
  // A copy refactors with the same solver and answers the same.
  const Linearization copy = sparse_linearization;
  Eigen::VectorXd dx_copy(n);
  copy.solve_minimum_norm(rhs, dx_copy);
  EXPECT_LT((dx_copy - dx).norm(), 1e-13 * dx.norm());
}

std::string solver_name(const ::testing::TestParamInfo<SparseLuSolver>& info) {
  return std::string(name(info.param));
}

INSTANTIATE_TEST_SUITE_P(AvailableSolvers, EverySparseLu,
                         ::testing::ValuesIn(available_sparse_lu_solvers()), solver_name);

TEST(SparseLuSolvers, NamesRoundTripAndEigenIsAlwaysAvailable) {
  EXPECT_TRUE(is_available(SparseLuSolver::Eigen));
  for (SparseLuSolver solver : all_sparse_lu_solvers()) {
    EXPECT_EQ(sparse_lu_solver_named(name(solver)), solver);
  }
  EXPECT_FALSE(sparse_lu_solver_named("mumps").has_value());
  EXPECT_EQ(available_sparse_lu_solvers().front(), SparseLuSolver::Eigen);
}

TEST(SparseLuSolvers, EnvironmentVariableChoosesTheSolverOrSaysWhatIsAvailable) {
  {
    const SolverEnvironment environment("");
    // Unset or empty: the built-in default, the one solver every build has.
    EXPECT_EQ(default_sparse_lu_solver(), SparseLuSolver::Eigen);
  }
  const SolverEnvironment environment("mumps");
  try {
    default_sparse_lu_solver();
    ADD_FAILURE() << "no exception";
  } catch (const InvalidArgument& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("TESSERA_SPARSE_LU = 'mumps'"), std::string::npos) << message;
    EXPECT_NE(message.find("eigen"), std::string::npos) << message;
  }
  for (SparseLuSolver solver : all_sparse_lu_solvers()) {
    if (!is_available(solver)) {
      const SolverEnvironment missing(name(solver));
      EXPECT_THROW(default_sparse_lu_solver(), InvalidArgument);
      EXPECT_THROW(make_sparse_lu(solver), InvalidArgument);
    }
  }
}

// The bordered Jacobian of a catalogue problem at (u = 0, λ = 1, ε = 0.1), bordered by the two
// parameter rows: its pattern is the one the covering factors.
template <typename Problem>
Eigen::SparseMatrix<double> bordered_catalogue_jacobian(const Problem& problem) {
  const int n = problem.ambient_dimension();
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  x(n - 2) = 1.0;
  x(n - 1) = 0.1;
  Eigen::SparseMatrix<double> J, A;
  problem.sparse_jacobian(x, J);
  bordered_jacobian(J, {{n - 2, n - 2, 1.0}, {n - 1, n - 1, 1.0}}, A);
  return A;
}

// KLU says what a factorisation holds: at least its factors, and no more than a few times them
// plus a workspace of n entries each. A matrix of singleton blocks (a diagonal, then a 2×2
// block) has blocks without LU arrays, whose sizes KLU never writes: they must not be read
// (they were, and the atlas then kept or dropped factorisations by heap garbage). The heap is
// filled with garbage first, so that such a read shows.
TEST(SparseLuSolvers, KluCountsTheBytesOfItsFactorisation) {
  if (!is_available(SparseLuSolver::Klu)) {
    GTEST_SKIP() << "KLU is not built in";
  }
  const int n = 50;
  std::vector<Eigen::Triplet<double>> entries;
  for (int i = 0; i < n - 2; ++i) {
    entries.emplace_back(i, i, 2.0 + i);
  }
  entries.emplace_back(n - 2, n - 2, 1.0);
  entries.emplace_back(n - 2, n - 1, 2.0);
  entries.emplace_back(n - 1, n - 2, 3.0);
  entries.emplace_back(n - 1, n - 1, 1.0);
  Eigen::SparseMatrix<double> A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  std::vector<std::size_t> bytes;
  for (int attempt = 0; attempt < 3; ++attempt) {
    {
      std::vector<std::vector<unsigned char>> garbage;
      for (int k = 0; k < 64; ++k) {
        garbage.emplace_back(64 + 16 * k, static_cast<unsigned char>(0xA5));
      }
    }
    auto lu = make_sparse_lu(SparseLuSolver::Klu);
    ASSERT_EQ(lu->analyze(A), SparseLuStatus::Success);
    ASSERT_EQ(lu->factorize(A), SparseLuStatus::Success);
    const std::optional<std::size_t> counted = lu->factorisation_bytes();
    ASSERT_TRUE(counted.has_value());
    const auto factors = static_cast<std::size_t>(lu->factor_nonzeros().value());
    EXPECT_GE(*counted, factors * sizeof(double));
    EXPECT_LE(*counted, 64 * sizeof(double) * static_cast<std::size_t>(n) + 16 * factors);
    bytes.push_back(*counted);
  }
  EXPECT_EQ(bytes[1], bytes[0]);
  EXPECT_EQ(bytes[2], bytes[0]);
}

// Without TESSERA_SPARSE_LU the solver follows the fill: KLU for a 1-D problem (fill 1.2×),
// Eigen's supernodal LU for a 2-D one on a fine grid (KLU predicts 7× and is slower there).
TEST(SparseLuSolvers, ChoosesKluForLowFillAndEigenForHighFill) {
  const SolverEnvironment unset("");
  const Eigen::SparseMatrix<double> one_d = bordered_catalogue_jacobian(ArrheniusBratu(2000));
  const Eigen::SparseMatrix<double> two_d = bordered_catalogue_jacobian(ArrheniusBratu2D(150));
  if (is_available(SparseLuSolver::Klu)) {
    EXPECT_EQ(sparse_lu_solver_for(one_d), SparseLuSolver::Klu);
    EXPECT_EQ(sparse_lu_solver_for(one_d), SparseLuSolver::Klu);  // remembered
  } else {
    EXPECT_EQ(sparse_lu_solver_for(one_d), SparseLuSolver::Eigen);
  }
  EXPECT_EQ(sparse_lu_solver_for(two_d), SparseLuSolver::Eigen);
  // The environment overrides the choice.
  const SolverEnvironment forced("eigen");
  EXPECT_EQ(sparse_lu_solver_for(one_d), SparseLuSolver::Eigen);
}

TEST(BorderedJacobian, CoordinateBorderPicksTheBestParametrisingPair) {
  Eigen::MatrixXd T = Eigen::MatrixXd::Zero(5, 2);
  T(1, 0) = 0.9;  // the largest row
  T(3, 0) = 0.3;
  T(4, 1) = 0.2;  // with row 1 the largest |det|
  T(2, 1) = 0.1;
  const JacobianBorder border = coordinate_border(T);
  ASSERT_EQ(border.size(), 2u);
  EXPECT_EQ(border[0].row(), 3);
  EXPECT_EQ(border[0].col(), 1);
  EXPECT_EQ(border[1].row(), 4);
  EXPECT_EQ(border[1].col(), 4);
  EXPECT_EQ(random_border(6).size(), 12u);
}

}  // namespace
}  // namespace tessera
