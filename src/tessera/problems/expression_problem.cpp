// SPDX-License-Identifier: MIT
#include "tessera/problems/expression_problem.h"

#include <utility>

#include "tessera/core/error.h"

namespace tessera {

ExpressionProblem::ExpressionProblem(std::string name, std::vector<Expression> equations,
                                     std::optional<Dynamics> dynamics)
    : name_(std::move(name)), equations_(std::move(equations)), dynamics_(std::move(dynamics)) {
  TESSERA_CHECK(!equations_.empty(), "ExpressionProblem '" << name_ << "' has no equations");
  variable_names_ = equations_.front().variable_names();
  const int n = static_cast<int>(variable_names_.size());
  TESSERA_CHECK(n >= 3, "ExpressionProblem '" << name_ << "' has " << n
                                              << " variables; a 2-manifold needs at least 3");
  TESSERA_CHECK(static_cast<int>(equations_.size()) == n - 2,
                "ExpressionProblem '" << name_ << "': " << n << " variables need n-2 = " << n - 2
                                      << " equations, found " << equations_.size());
  for (std::size_t i = 1; i < equations_.size(); ++i) {
    TESSERA_CHECK(equations_[i].variable_names() == variable_names_,
                  "ExpressionProblem '" << name_ << "': equation " << i + 1
                                        << " has other variables than equation 1");
  }
  if (dynamics_) {
    check_dynamics(*dynamics_, n, name_);
  }
}

namespace {

// Scratch per thread (one workspace serves any expressions, one thread at a time), so that the
// problem is thread-safe; after a thread's first evaluation nothing is allocated.
ExpressionWorkspace& thread_workspace() {
  thread_local ExpressionWorkspace workspace;
  return workspace;
}

}  // namespace

void ExpressionProblem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::VectorXd> F) const {
  TESSERA_CHECK(F.size() == static_cast<Eigen::Index>(equations_.size()),
                "F has size " << F.size() << ", expected " << equations_.size());
  ExpressionWorkspace& workspace = thread_workspace();
  for (std::size_t i = 0; i < equations_.size(); ++i) {
    F(static_cast<Eigen::Index>(i)) = equations_[i].value(x, workspace);
  }
}

void ExpressionProblem::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                 Eigen::Ref<Eigen::MatrixXd> J) const {
  TESSERA_CHECK(
      J.rows() == static_cast<Eigen::Index>(equations_.size()) && J.cols() == ambient_dimension(),
      "J is " << J.rows() << "×" << J.cols() << ", expected " << equations_.size() << "×"
              << ambient_dimension());
  ExpressionWorkspace& workspace = thread_workspace();
  thread_local Eigen::VectorXd gradient;
  gradient.resize(ambient_dimension());
  for (std::size_t i = 0; i < equations_.size(); ++i) {
    // Rows of a column-major J are strided, so the gradient goes through a contiguous vector.
    equations_[i].value_and_gradient(x, gradient, workspace);
    J.row(static_cast<Eigen::Index>(i)) = gradient.transpose();
  }
}

}  // namespace tessera
