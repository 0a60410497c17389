// SPDX-License-Identifier: MIT
#include "tessera/methods/stability/state_jacobian.h"

#include <cmath>

#include "tessera/core/error.h"

namespace tessera {

Dynamics required_dynamics(const ImplicitProblem& problem, const std::string& request) {
  const std::optional<Dynamics> dynamics = problem.dynamics();
  TESSERA_CHECK(dynamics.has_value(),
                request << ": problem '" << problem.name()
                        << "' does not say what its equations are the right-hand side of. "
                           "Stability needs dynamics B·u' = ±F(u, p) with two parameters p: a "
                           "problem file declares them with a line `dynamics parameters P1 P2` "
                           "(docs/problem-files.md), a Python problem with "
                           "tessera.Problem(..., dynamics=...) (docs/python.md), a C++ problem "
                           "by overriding ImplicitProblem::dynamics()");
  check_dynamics(*dynamics, problem.ambient_dimension(), problem.name());
  return *dynamics;
}

StateJacobian::StateJacobian(const ImplicitProblem& problem, const std::string& request)
    : problem_(problem),
      dynamics_(required_dynamics(problem, request)),
      states_(state_indices(dynamics_, problem.ambient_dimension())),
      is_sparse_(problem.has_sparse_jacobian()),
      mass_(mass_matrix(dynamics_, static_cast<int>(states_.size()))) {
  if (dynamics_.mass_diagonal.size() > 0) {
    has_positive_diagonal_mass_ = (dynamics_.mass_diagonal.array() > 0.0).all();
  } else if (dynamics_.mass_matrix.size() > 0) {
    has_positive_diagonal_mass_ = false;  // a general matrix: no shortcut taken
  }
}

bool StateJacobian::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x) {
  const int m = state_count();
  const int n = problem_.ambient_dimension();
  ++jacobian_evaluations_;
  if (is_sparse_) {
    problem_.sparse_jacobian(x, full_sparse_);
    // The state columns, in order: a copy of m of the n compressed columns.
    sparse_.resize(m, m);
    sparse_.reserve(full_sparse_.nonZeros());
    std::vector<Eigen::Triplet<double>> entries;
    entries.reserve(static_cast<std::size_t>(full_sparse_.nonZeros()));
    for (int j = 0; j < m; ++j) {
      for (Eigen::SparseMatrix<double>::InnerIterator it(full_sparse_, states_[static_cast<std::size_t>(j)]);
           it; ++it) {
        entries.emplace_back(static_cast<int>(it.row()), j, dynamics_.sign * it.value());
      }
    }
    sparse_.setFromTriplets(entries.begin(), entries.end());
    sparse_.makeCompressed();
    for (int k = 0; k < sparse_.nonZeros(); ++k) {
      if (!std::isfinite(sparse_.valuePtr()[k])) {
        return false;
      }
    }
    return true;
  }
  full_dense_.resize(m, n);
  problem_.jacobian(x, full_dense_);
  dense_.resize(m, m);
  for (int j = 0; j < m; ++j) {
    dense_.col(j) = dynamics_.sign * full_dense_.col(states_[static_cast<std::size_t>(j)]);
  }
  return dense_.allFinite();
}

Eigen::MatrixXd StateJacobian::as_dense() const {
  return is_sparse_ ? Eigen::MatrixXd(sparse_) : dense_;
}

}  // namespace tessera
