// SPDX-License-Identifier: MIT
#include "tessera/core/bordered_jacobian.h"

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
  std::vector<Eigen::Triplet<double>> entries;
  entries.reserve(J.nonZeros() + border.size());
  for (int k = 0; k < J.outerSize(); ++k) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, k); it; ++it) {
      entries.emplace_back(static_cast<int>(it.row()), static_cast<int>(it.col()), it.value());
    }
  }
  for (const auto& entry : border) {
    TESSERA_CHECK(entry.row() == n - 2 || entry.row() == n - 1,
                  "bordered_jacobian: a border entry is in row " << entry.row() << ", must be "
                                                                 << n - 2 << " or " << n - 1);
  }
  entries.insert(entries.end(), border.begin(), border.end());
  A.resize(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  A.makeCompressed();
}

}  // namespace tessera
