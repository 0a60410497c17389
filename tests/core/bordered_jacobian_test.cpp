// SPDX-License-Identifier: MIT
// The bordered matrix [J; border] written column by column equals the one assembled from
// triplets, for coordinate borders, dense random borders and borders with repeated entries.
#include "tessera/core/bordered_jacobian.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "tessera/core/error.h"

namespace {

Eigen::SparseMatrix<double> random_sparse(int rows, int cols, double density, unsigned seed) {
  std::srand(seed);
  Eigen::MatrixXd dense = Eigen::MatrixXd::Random(rows, cols);
  dense = dense.unaryExpr([&](double x) { return std::abs(x) < density ? x : 0.0; });
  return dense.sparseView();
}

Eigen::MatrixXd by_triplets(const Eigen::SparseMatrix<double>& J,
                            const tessera::JacobianBorder& border) {
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(J.cols(), J.cols());
  A.topRows(J.rows()) = Eigen::MatrixXd(J);
  for (const auto& entry : border) {
    A(entry.row(), entry.col()) += entry.value();
  }
  return A;
}

TEST(BorderedJacobian, EqualsTheMatrixAssembledFromTriplets) {
  const int n = 40;
  const Eigen::SparseMatrix<double> J = random_sparse(n - 2, n, 0.2, 3);
  const std::vector<tessera::JacobianBorder> borders = {
      {{n - 2, 5, 1.0}, {n - 1, 17, 1.0}},
      {{n - 1, 17, 1.0}, {n - 2, 5, 1.0}},                       // any order
      {{n - 2, 0, 1.0}, {n - 1, n - 1, 2.0}, {n - 2, 0, 0.5}},   // a repeated entry is summed
      tessera::random_border(n),
  };
  Eigen::SparseMatrix<double> A;
  for (const auto& border : borders) {
    tessera::bordered_jacobian(J, border, A);  // A is reused across borders
    EXPECT_EQ((Eigen::MatrixXd(A) - by_triplets(J, border)).cwiseAbs().maxCoeff(), 0.0);
    EXPECT_TRUE(A.isCompressed());
    for (int k = 0; k < A.outerSize(); ++k) {
      for (int p = A.outerIndexPtr()[k] + 1; p < A.outerIndexPtr()[k + 1]; ++p) {
        EXPECT_LT(A.innerIndexPtr()[p - 1], A.innerIndexPtr()[p]) << "rows sorted in column " << k;
      }
    }
  }
}

TEST(BorderedJacobian, RejectsABorderOutsideItsRowsOrColumns) {
  const int n = 10;
  const Eigen::SparseMatrix<double> J = random_sparse(n - 2, n, 0.5, 4);
  Eigen::SparseMatrix<double> A;
  EXPECT_THROW(tessera::bordered_jacobian(J, {{n - 3, 0, 1.0}}, A), tessera::InvalidArgument);
  EXPECT_THROW(tessera::bordered_jacobian(J, {{n - 1, n, 1.0}}, A), tessera::InvalidArgument);
}

}  // namespace
