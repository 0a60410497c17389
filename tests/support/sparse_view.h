// SPDX-License-Identifier: MIT
// A dense problem seen through a sparse Jacobian, for tests of the sparse paths (the ones a
// discretised PDE takes: bordered LU, kept factorisations, the sparse filters of the checks).
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "tessera/core/implicit_problem.h"

namespace tessera::testing {

/// Evaluates F and DF as `inner` (which must outlive the view) and says it has a sparse
/// Jacobian, assembled from the dense one.
class SparseView final : public ImplicitProblem {
 public:
  explicit SparseView(const ImplicitProblem& inner) : inner_(inner) {}
  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::VectorXd> F) const override {
    inner_.evaluate(x, F);
  }
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                Eigen::Ref<Eigen::MatrixXd> J) const override {
    inner_.jacobian(x, J);
  }
  bool has_sparse_jacobian() const override { return true; }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                       Eigen::SparseMatrix<double>& J) const override {
    Eigen::MatrixXd dense(ambient_dimension() - 2, ambient_dimension());
    inner_.jacobian(x, dense);
    J = dense.sparseView();
  }

 private:
  const ImplicitProblem& inner_;
};

}  // namespace tessera::testing
