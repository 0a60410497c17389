// SPDX-License-Identifier: MIT
// An ImplicitProblem whose n-2 equations are Expressions: what a problem file turns into.
#pragma once

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "tessera/core/implicit_problem.h"
#include "tessera/problems/expression.h"

namespace tessera {

/// F(x) = (f_1(x), …, f_{n-2}(x)) with each f_i an Expression of the same n variables, and a
/// dense Jacobian whose rows are the exact gradients ∇f_i (reverse-mode differentiation).
///
/// Evaluation reuses a workspace per thread, so after a thread's first call `evaluate` and
/// `jacobian` do not allocate; a pure function of x, thread-safe.
class ExpressionProblem final : public ImplicitProblem {
 public:
  /// \param name       short identifier returned by name(), e.g. "sphere_cut".
  /// \param equations  n-2 expressions, all of the same variables (same names, same order).
  /// \param dynamics   the dynamics B·u' = ±F(u, p) whose steady states M is (a problem file's
  ///                   `dynamics` line); none: the problem declares none.
  /// \pre  n = equations[0].variable_count() >= 3 and equations.size() == n-2.
  /// \throw InvalidArgument if a precondition fails (the message names the counts or the names)
  ///        or the dynamics are invalid (check_dynamics).
  ExpressionProblem(std::string name, std::vector<Expression> equations,
                    std::optional<Dynamics> dynamics = std::nullopt);

  int ambient_dimension() const override { return static_cast<int>(variable_names_.size()); }
  /// F(x). \pre x.size() == n, F.size() == n-2.
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  /// J = DF(x), (n-2)×n, row i = ∇f_i(x). \pre x.size() == n, J is (n-2)×n.
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  std::string name() const override { return name_; }
  /// The variable names of the expressions, e.g. {"x1", "x2", "Da", "B"}.
  std::vector<std::string> coordinate_names() const override { return variable_names_; }
  std::optional<Dynamics> dynamics() const override { return dynamics_; }
  bool is_thread_safe() const override { return true; }

  const std::vector<Expression>& equations() const { return equations_; }

 private:
  std::string name_;
  std::vector<std::string> variable_names_;
  std::vector<Expression> equations_;
  std::optional<Dynamics> dynamics_;
};

}  // namespace tessera
