// SPDX-License-Identifier: MIT
// What a problem's equations are the right-hand side of: B·u' = s·F(u, p), with two parameters p
// among the n coordinates and the other n − 2 the state u. M is then the surface of steady states,
// and the eigenvalues of the pencil (s·D_uF, B) say which of them are stable.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <array>
#include <string>
#include <vector>

namespace tessera {

/// The dynamics B·u' = sign·F(u, p) whose steady states are M.
///
/// The state u is the n − 2 coordinates that are not parameters, in their order; equation i of
/// F belongs to row i of B. A steady state is (linearly) stable when every finite eigenvalue μ of
/// sign·D_uF·v = μ·B·v has a negative real part.
struct Dynamics {
  /// Indices among the n coordinates of the two parameters p₁, p₂ (distinct, 0 … n−1).
  std::array<int, 2> parameters{-1, -1};
  /// +1: B·u' = F as written; −1: B·u' = −F (e.g. F = ∇V of a potential V that the dynamics
  /// descends, as for Whitney's pleat).
  double sign = 1.0;
  /// B as a diagonal (n − 2 entries ≥ 0, zeros for algebraic equations); empty: see mass_matrix.
  Eigen::VectorXd mass_diagonal;
  /// B as a sparse (n − 2)×(n − 2) matrix; used when mass_diagonal is empty and this is not.
  /// Both empty: B = I.
  Eigen::SparseMatrix<double> mass_matrix;

  bool has_identity_mass() const { return mass_diagonal.size() == 0 && mass_matrix.size() == 0; }
};

/// The state coordinates (every index 0 … n−1 but the two parameters), in order.
std::vector<int> state_indices(const Dynamics& dynamics, int n);

/// Checks the dynamics against a problem of dimension n named `problem_name`.
/// \throw InvalidArgument naming the problem and what is wrong: parameters out of range or equal,
///        a sign other than ±1, a mass matrix of the wrong size or with a non-finite or (diagonal)
///        negative entry.
void check_dynamics(const Dynamics& dynamics, int n, const std::string& problem_name);

/// B as a sparse matrix (the identity when none is given).
Eigen::SparseMatrix<double> mass_matrix(const Dynamics& dynamics, int state_count);

}  // namespace tessera
