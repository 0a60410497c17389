// SPDX-License-Identifier: MIT
// The nested-dissection ordering of Eigen's SparseLU: a permutation with the parameters last,
// one ordering for every border of a pattern, and about half of COLAMD's fill on a 2-D PDE.
#include "tessera/core/detail/nested_dissection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <numeric>
#include <thread>

#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/sparse_lu.h"
#include "tessera/problems/examples.h"

namespace tessera {
namespace {

// bratu2d's Jacobian at a state off the trivial branch, bordered by e_iᵀ (a grid value) and
// e_jᵀ, as Linearization borders it near a fold.
Eigen::SparseMatrix<double> bordered_bratu2d(const ArrheniusBratu2D& problem, int i, int j) {
  const int n = problem.ambient_dimension();
  Eigen::VectorXd x = Eigen::VectorXd::Constant(n, 0.3);
  x(n - 2) = 1.5;  // λ
  x(n - 1) = 0.1;  // ε
  Eigen::SparseMatrix<double> J, A;
  problem.sparse_jacobian(x, J);
  bordered_jacobian(J, {{n - 2, i, 1.0}, {n - 1, j, 1.0}}, A);
  return A;
}

// Sets TESSERA_SPARSE_LU_ORDERING for one scope.
class OrderingEnvironment {
 public:
  explicit OrderingEnvironment(const char* value) { setenv("TESSERA_SPARSE_LU_ORDERING", value, 1); }
  ~OrderingEnvironment() { unsetenv("TESSERA_SPARSE_LU_ORDERING"); }
};

struct Factored {
  long fill = 0;
  Eigen::VectorXd x;
};

Factored factor_with_eigen(const Eigen::SparseMatrix<double>& A, const Eigen::VectorXd& b) {
  auto lu = make_sparse_lu(SparseLuSolver::Eigen);
  EXPECT_EQ(lu->analyze(A), SparseLuStatus::Success);
  EXPECT_EQ(lu->factorize(A), SparseLuStatus::Success) << lu->last_message();
  Factored result;
  result.fill = lu->factor_nonzeros().value_or(0);
  result.x.resize(b.size());
  lu->solve(b, result.x);
  return result;
}

TEST(NestedDissection, IsAPermutationWithTheParameterColumnsLast) {
  if (!detail::has_nested_dissection()) {
    GTEST_SKIP() << "this build has no METIS";
  }
  const ArrheniusBratu2D problem(40);
  const int n = problem.ambient_dimension();
  const std::vector<int> order = detail::nested_dissection_ordering(bordered_bratu2d(problem, 820, n - 1));
  ASSERT_EQ(static_cast<int>(order.size()), n);
  std::vector<int> sorted = order;
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(n);
  std::iota(identity.begin(), identity.end(), 0);
  EXPECT_EQ(sorted, identity);
  // λ and ε appear in every equation: quasi-dense, eliminated last.
  EXPECT_EQ(order[n - 2], n - 2);
  EXPECT_EQ(order[n - 1], n - 1);
}

// Graphs without edges (a diagonal matrix, a 1×1 one) and a matrix of only dense columns are
// orderings too, not failures or crashes in METIS.
TEST(NestedDissection, OrdersDegenerateGraphs) {
  if (!detail::has_nested_dissection()) {
    GTEST_SKIP() << "this build has no METIS";
  }
  for (int n : {1, 2, 7}) {
    Eigen::SparseMatrix<double> D(n, n);
    D.setIdentity();
    D.makeCompressed();
    const std::vector<int> order = detail::nested_dissection_ordering(D);
    std::vector<int> sorted = order;
    std::sort(sorted.begin(), sorted.end());
    std::vector<int> identity(n);
    std::iota(identity.begin(), identity.end(), 0);
    EXPECT_EQ(sorted, identity) << "n = " << n;
    const Factored solved = factor_with_eigen(D, Eigen::VectorXd::Ones(n));
    EXPECT_EQ(solved.x, Eigen::VectorXd::Ones(n));
  }
  Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(40, 40);
  dense.col(3).setConstant(2.0);
  dense.row(5).setConstant(3.0);
  dense(3, 3) = 4.0;
  const Eigen::SparseMatrix<double> A = dense.sparseView();
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(40, 1.0, 2.0);
  const Factored solved = factor_with_eigen(A, b);
  EXPECT_LT((A * solved.x - b).norm(), 1e-12 * b.norm());
}

// The border rows are the parameters' rows, left out of the graph with them: every border gives
// the same ordering, so the covering runs METIS once per pattern. A fresh thread (no remembered
// graph) computes the same ordering: runs are deterministic.
TEST(NestedDissection, EveryBorderAndEveryThreadGetTheSameOrdering) {
  if (!detail::has_nested_dissection()) {
    GTEST_SKIP() << "this build has no METIS";
  }
  const ArrheniusBratu2D problem(30);
  const int n = problem.ambient_dimension();
  const std::vector<int> first = detail::nested_dissection_ordering(bordered_bratu2d(problem, 450, n - 1));
  const std::vector<int> second = detail::nested_dissection_ordering(bordered_bratu2d(problem, 17, n - 2));
  EXPECT_EQ(first, second);
  std::vector<int> elsewhere;
  std::thread([&] { elsewhere = detail::nested_dissection_ordering(bordered_bratu2d(problem, 17, n - 2)); }).join();
  EXPECT_EQ(first, elsewhere);
}

// bratu2d N = 100 (n = 10⁴): COLAMD fills 666 k entries, nested dissection 403 k (section 9 of
// bench/history/RESULTS-log.md); both solve the system to rounding.
TEST(NestedDissection, HalvesTheFillOfColamdOnA2dPdeAndSolvesTheSameSystem) {
  if (!detail::has_nested_dissection()) {
    GTEST_SKIP() << "this build has no METIS";
  }
  const ArrheniusBratu2D problem(100);
  const int n = problem.ambient_dimension();
  const Eigen::SparseMatrix<double> A = bordered_bratu2d(problem, 5050, n - 1);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(n, -1.0, 1.0);
  const Factored nested = factor_with_eigen(A, b);
  Factored colamd;
  {
    const OrderingEnvironment environment("colamd");
    colamd = factor_with_eigen(A, b);
  }
  EXPECT_LT(nested.fill, 0.7 * colamd.fill) << nested.fill << " against " << colamd.fill;
  EXPECT_LT((A * nested.x - b).norm(), 1e-12 * A.norm() * nested.x.norm());
  EXPECT_LT((nested.x - colamd.x).norm(), 1e-10 * colamd.x.norm());
}

}  // namespace
}  // namespace tessera
