// SPDX-License-Identifier: MIT
// A decorator that counts evaluations of F and of its Jacobian, for summaries and benchmarks.
#pragma once

#include "tessera/core/implicit_problem.h"

namespace tessera {

/// Forwards to `inner` and counts calls. Methods wrap the user's problem in one of these.
class CountedProblem final : public ImplicitProblem {
 public:
  explicit CountedProblem(const ImplicitProblem& inner) : inner_(inner) {}

  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    ++function_evaluations_;
    inner_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    ++jacobian_evaluations_;
    inner_.jacobian(x, J);
  }
  bool has_sparse_jacobian() const override { return inner_.has_sparse_jacobian(); }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    ++jacobian_evaluations_;
    inner_.sparse_jacobian(x, J);
  }
  std::string name() const override { return inner_.name(); }
  std::vector<std::string> coordinate_names() const override { return inner_.coordinate_names(); }

  long function_evaluations() const { return function_evaluations_; }
  long jacobian_evaluations() const { return jacobian_evaluations_; }

 private:
  const ImplicitProblem& inner_;
  mutable long function_evaluations_ = 0;
  mutable long jacobian_evaluations_ = 0;
};

}  // namespace tessera
