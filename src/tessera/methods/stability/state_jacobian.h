// SPDX-License-Identifier: MIT
// The linearisation of a problem's dynamics at a point: A = s·D_uF(x) (the columns of DF that
// belong to the state u, times the sign) and the mass matrix B, dense or sparse as the problem's
// Jacobian is. Shared by the stability counts and the Hopf curves.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <string>
#include <vector>

#include "tessera/core/dynamics.h"
#include "tessera/core/implicit_problem.h"

namespace tessera {

/// The dynamics of `problem`, checked. `request` names what needs them in the message
/// ("--stability").
/// \throw InvalidArgument if the problem declares none (the message says how to declare them:
///        problem files, Python, C++) or they are invalid.
Dynamics required_dynamics(const ImplicitProblem& problem, const std::string& request);

class StateJacobian {
 public:
  /// \throw InvalidArgument as required_dynamics.
  StateJacobian(const ImplicitProblem& problem, const std::string& request);

  const Dynamics& dynamics() const { return dynamics_; }
  int state_count() const { return static_cast<int>(states_.size()); }
  const std::vector<int>& states() const { return states_; }
  /// True when A is kept sparse (the problem's Jacobian is).
  bool is_sparse() const { return is_sparse_; }

  /// A = s·D_uF(x): sparse() or dense() as is_sparse() says. Returns false if DF is not finite.
  bool evaluate(const Eigen::Ref<const Eigen::VectorXd>& x);
  const Eigen::SparseMatrix<double>& sparse() const { return sparse_; }
  const Eigen::MatrixXd& dense() const { return dense_; }
  /// A as a dense matrix, whichever form it is kept in.
  Eigen::MatrixXd as_dense() const;

  /// B, sparse (the identity when the problem gives none).
  const Eigen::SparseMatrix<double>& mass() const { return mass_; }
  bool has_identity_mass() const { return dynamics_.has_identity_mass(); }
  /// B is diagonal with positive entries (or the identity).
  bool has_positive_diagonal_mass() const { return has_positive_diagonal_mass_; }

  long jacobian_evaluations() const { return jacobian_evaluations_; }

 private:
  const ImplicitProblem& problem_;
  Dynamics dynamics_;
  std::vector<int> states_;
  bool is_sparse_ = false;
  bool has_positive_diagonal_mass_ = true;
  Eigen::SparseMatrix<double> mass_;
  Eigen::SparseMatrix<double> full_sparse_;  // DF, (n−2)×n
  Eigen::MatrixXd full_dense_;
  Eigen::SparseMatrix<double> sparse_;
  Eigen::MatrixXd dense_;
  long jacobian_evaluations_ = 0;
};

}  // namespace tessera
