// SPDX-License-Identifier: MIT
#include "tessera/core/implicit_problem.h"

#include <cmath>

#include "tessera/core/ambient_space.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization_backend.h"

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

Eigen::VectorXd metric_weights(const ImplicitProblem& problem) {
  const int n = problem.ambient_dimension();
  Eigen::VectorXd weights = Eigen::VectorXd::Ones(n);
  std::vector<bool> taken(n, false);
  bool is_euclidean = true;
  for (const CoordinateBlock& block : problem.coordinate_blocks()) {
    TESSERA_CHECK(block.first >= 0 && block.size >= 1 && block.first <= n - block.size,
                  "problem '" << problem.name() << "': coordinate block '" << block.name
                              << "' (first " << block.first << ", size " << block.size
                              << ") does not lie in the coordinates 0 … " << n - 1);
    TESSERA_CHECK(std::isfinite(block.weight) && block.weight > 0,
                  "problem '" << problem.name() << "': coordinate block '" << block.name
                              << "' has weight " << block.weight
                              << "; it must be a finite number > 0");
    for (int i = block.first; i < block.first + block.size; ++i) {
      TESSERA_CHECK(!taken[i], "problem '" << problem.name() << "': coordinate block '"
                                           << block.name << "' overlaps another block at "
                                           << "coordinate " << i);
      taken[i] = true;
      weights(i) = block.weight;
    }
    is_euclidean = is_euclidean && block.weight == 1.0;
  }
  return is_euclidean ? Eigen::VectorXd() : weights;
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

std::shared_ptr<const AmbientSpace> ImplicitProblem::space() const {
  // The correctors ask at every call (millions at n = 3): one R^n per thread and dimension.
  thread_local std::shared_ptr<const AmbientSpace> last;
  const int n = ambient_dimension();
  if (!last || last->dimension() != n) {
    last = std::make_shared<AmbientSpace>(n);
  }
  return last;
}

std::unique_ptr<LinearizationBackend> ImplicitProblem::make_linearization_backend() const {
  return nullptr;
}

}  // namespace tessera
