// SPDX-License-Identifier: MIT
#include "tessera/core/bordered_jacobian.h"

#include <algorithm>
#include <random>

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
