// SPDX-License-Identifier: MIT
#include "tessera/core/dynamics.h"

#include <cmath>

#include "tessera/core/error.h"

namespace tessera {

std::vector<int> state_indices(const Dynamics& dynamics, int n) {
  std::vector<int> states;
  states.reserve(static_cast<std::size_t>(std::max(n - 2, 0)));
  for (int i = 0; i < n; ++i) {
    if (i != dynamics.parameters[0] && i != dynamics.parameters[1]) {
      states.push_back(i);
    }
  }
  return states;
}

void check_dynamics(const Dynamics& dynamics, int n, const std::string& problem_name) {
  const auto [p, q] = dynamics.parameters;
  TESSERA_CHECK(p >= 0 && p < n && q >= 0 && q < n,
                "problem '" << problem_name << "': the parameters of its dynamics must be two of "
                            << "its " << n << " coordinates (indices 0 … " << n - 1 << "), got "
                            << p << " and " << q);
  TESSERA_CHECK(p != q, "problem '" << problem_name
                                    << "': the two parameters of its dynamics are the same "
                                       "coordinate (index "
                                    << p << ")");
  TESSERA_CHECK(dynamics.sign == 1.0 || dynamics.sign == -1.0,
                "problem '" << problem_name << "': the sign of its dynamics (B·u' = s·F) must be "
                            << "+1 or −1, got " << dynamics.sign);
  const int m = n - 2;
  if (dynamics.mass_diagonal.size() > 0) {
    TESSERA_CHECK(dynamics.mass_diagonal.size() == m,
                  "problem '" << problem_name << "': its mass matrix diagonal has "
                              << dynamics.mass_diagonal.size() << " entries, one per state ("
                              << m << ") is needed");
    for (int i = 0; i < m; ++i) {
      const double b = dynamics.mass_diagonal(i);
      TESSERA_CHECK(std::isfinite(b) && b >= 0.0,
                    "problem '" << problem_name << "': mass matrix entry " << i << " is " << b
                                << "; the diagonal of B must be finite and ≥ 0 (0: an algebraic "
                                   "equation)");
    }
  } else if (dynamics.mass_matrix.size() > 0) {
    TESSERA_CHECK(dynamics.mass_matrix.rows() == m && dynamics.mass_matrix.cols() == m,
                  "problem '" << problem_name << "': its mass matrix is "
                              << dynamics.mass_matrix.rows() << "×" << dynamics.mass_matrix.cols()
                              << ", the number of states is " << m);
    for (int k = 0; k < dynamics.mass_matrix.outerSize(); ++k) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(dynamics.mass_matrix, k); it; ++it) {
        TESSERA_CHECK(std::isfinite(it.value()),
                      "problem '" << problem_name << "': mass matrix entry (" << it.row() << ", "
                                  << it.col() << ") is not finite");
      }
    }
  }
}

Eigen::SparseMatrix<double> mass_matrix(const Dynamics& dynamics, int state_count) {
  Eigen::SparseMatrix<double> B(state_count, state_count);
  if (dynamics.mass_diagonal.size() > 0) {
    std::vector<Eigen::Triplet<double>> entries;
    for (int i = 0; i < state_count; ++i) {
      entries.emplace_back(i, i, dynamics.mass_diagonal(i));
    }
    B.setFromTriplets(entries.begin(), entries.end());
  } else if (dynamics.mass_matrix.size() > 0) {
    B = dynamics.mass_matrix;
  } else {
    B.setIdentity();
  }
  B.makeCompressed();
  return B;
}

}  // namespace tessera
