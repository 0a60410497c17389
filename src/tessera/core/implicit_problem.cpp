// SPDX-License-Identifier: MIT
#include "tessera/core/implicit_problem.h"

#include "tessera/core/error.h"

namespace tessera {

void ImplicitProblem::jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                               Eigen::Ref<Eigen::MatrixXd> J) const {
  // Guard against a problem that implements neither form: the two defaults would recurse.
  TESSERA_CHECK(has_sparse_jacobian(), "problem '" << name()
                                                   << "' implements neither jacobian() nor "
                                                      "sparse_jacobian() with has_sparse_jacobian()");
  Eigen::SparseMatrix<double> sparse;
  sparse_jacobian(x, sparse);
  J = Eigen::MatrixXd(sparse);
}

void ImplicitProblem::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& x,
                                      Eigen::SparseMatrix<double>& J) const {
  TESSERA_CHECK(!has_sparse_jacobian(), "problem '" << name()
                                                    << "' says has_sparse_jacobian() but does "
                                                       "not implement sparse_jacobian()");
  const int n = ambient_dimension();
  Eigen::MatrixXd dense(n - 2, n);
  jacobian(x, dense);
  J = dense.sparseView();
}

std::vector<std::string> ImplicitProblem::coordinate_names() const {
  return default_coordinate_names(ambient_dimension());
}

std::vector<std::string> default_coordinate_names(int n) {
  if (n == 3) {
    return {"x", "y", "z"};
  }
  std::vector<std::string> names;
  names.reserve(n);
  for (int i = 0; i < n; ++i) {
    names.push_back("x" + std::to_string(i));
  }
  return names;
}

}  // namespace tessera
