// SPDX-License-Identifier: MIT
#include "tessera/core/bordered_jacobian.h"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <random>
#include <utility>

#include "tessera/core/error.h"

namespace tessera {

JacobianBorder coordinate_border(const Eigen::MatrixXd& T) {
  const int n = static_cast<int>(T.rows());
  TESSERA_CHECK(n >= 2 && T.cols() == 2, "coordinate_border: T is " << T.rows() << "×" << T.cols()
                                                                    << ", must be n×2, n >= 2");
  int i = 0;
  T.rowwise().squaredNorm().maxCoeff(&i);
  int j = i == 0 ? 1 : 0;
  double best = -1.0;
  for (int k = 0; k < n; ++k) {
    const double det = std::abs(T(i, 0) * T(k, 1) - T(i, 1) * T(k, 0));
    if (k != i && det > best) {
      best = det;
      j = k;
    }
  }
  return {{n - 2, i, 1.0}, {n - 1, j, 1.0}};
}

bool coordinate_tangent_basis(Eigen::MatrixXd& kernel, const Eigen::MatrixXd* guide) {
  const int n = static_cast<int>(kernel.rows());
  int i = n - 2;
  int j = n - 1;
  if (guide != nullptr) {
    const JacobianBorder border = coordinate_border(*guide);
    i = border[0].col();
    j = border[1].col();
  }
  Eigen::Matrix2d rows;
  rows << kernel.row(i), kernel.row(j);
  // Singular to working precision relative to the basis: the sparse backend's LU would fail too.
  if (!(std::abs(rows.determinant()) > 1e-12 * kernel.squaredNorm())) {
    return false;
  }
  Eigen::MatrixXd basis = kernel * rows.inverse();
  basis.row(i) = Eigen::RowVector2d(1.0, 0.0);
  basis.row(j) = Eigen::RowVector2d(0.0, 1.0);
  // Modified Gram–Schmidt, twice, as the sparse backend orthonormalises A⁻¹ [e_{n−2}, e_{n−1}].
  for (int pass = 0; pass < 2; ++pass) {
    basis.col(0).normalize();
    basis.col(1) -= basis.col(0).dot(basis.col(1)) * basis.col(0);
    basis.col(1).normalize();
  }
  if (!basis.allFinite()) {
    return false;
  }
  kernel = std::move(basis);
  return true;
}

bool coordinate_tangent_basis(Eigen::MatrixXd& kernel, const Eigen::MatrixXd* reference,
                              Eigen::MatrixXd& last) {
  const Eigen::MatrixXd* guide =
      reference != nullptr ? reference : last.rows() == kernel.rows() ? &last : nullptr;
  if (!coordinate_tangent_basis(kernel, guide) && !coordinate_tangent_basis(kernel, nullptr)) {
    return false;
  }
  last = kernel;
  return true;
}

JacobianBorder random_border(int n) {
  // A fixed seed keeps runs deterministic.
  std::mt19937_64 generator(20261121);
  std::normal_distribution<double> normal;
  JacobianBorder border;
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < n; ++i) {
      border.emplace_back(n - 2 + j, i, normal(generator));
    }
  }
  return border;
}

void bordered_jacobian(const Eigen::SparseMatrix<double>& J, const JacobianBorder& border,
                       Eigen::SparseMatrix<double>& A) {
  const int n = static_cast<int>(J.cols());
  TESSERA_CHECK(J.rows() == n - 2,
                "bordered_jacobian: J is " << J.rows() << "×" << J.cols() << ", must be (n−2)×n");
  for (const auto& entry : border) {
    TESSERA_CHECK(entry.row() == n - 2 || entry.row() == n - 1,
                  "bordered_jacobian: a border entry is in row " << entry.row() << ", must be "
                                                                 << n - 2 << " or " << n - 1);
    TESSERA_CHECK(entry.col() >= 0 && entry.col() < n,
                  "bordered_jacobian: a border entry is in column " << entry.col() << " of " << n);
  }
  // The border, by column and row, repeated entries summed.
  JacobianBorder sorted = border;
  std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) {
    return a.col() != b.col() ? a.col() < b.col() : a.row() < b.row();
  });
  JacobianBorder merged;
  for (const auto& entry : sorted) {
    if (!merged.empty() && merged.back().col() == entry.col() &&
        merged.back().row() == entry.row()) {
      merged.back() = {entry.row(), entry.col(), merged.back().value() + entry.value()};
    } else {
      merged.push_back(entry);
    }
  }
  // The compressed columns written directly: column k of A is column k of J (its rows, all
  // below n − 2, in the order J keeps them) followed by the border rows n − 2, n − 1. A reused
  // A keeps its storage (resize keeps it for an unchanged shape); no triplets, no transposes.
  A.resize(n, n);
  A.resizeNonZeros(J.nonZeros() + static_cast<Eigen::Index>(merged.size()));
  int* outer = A.outerIndexPtr();
  int* inner = A.innerIndexPtr();
  double* values = A.valuePtr();
  Eigen::Index k = 0;
  std::size_t b = 0;
  for (int column = 0; column < n; ++column) {
    outer[column] = static_cast<int>(k);
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, column); it; ++it) {
      inner[k] = static_cast<int>(it.row());
      values[k++] = it.value();
    }
    for (; b < merged.size() && merged[b].col() == column; ++b) {
      inner[k] = merged[b].row();
      values[k++] = merged[b].value();
    }
  }
  outer[n] = static_cast<int>(k);
  A.resizeNonZeros(k);
}

}  // namespace tessera
