// SPDX-License-Identifier: MIT
#include "tessera/core/scaled_problem.h"

#include <cmath>

#include "tessera/core/ambient_space.h"
#include "tessera/core/error.h"

namespace tessera {

ScaledProblem::ScaledProblem(const ImplicitProblem& inner, Eigen::VectorXd weights)
    : inner_(inner), weights_(std::move(weights)) {
  // A distributed problem scales itself (its weights are split like its rows):
  // petsc::DistributedProblem presents the metric's coordinates already.
  TESSERA_CHECK(!inner.space()->is_distributed(),
                "ScaledProblem: problem '" << inner.name()
                                           << "' is distributed; it must present scaled coordinates itself");
  TESSERA_CHECK(weights_.size() == inner.ambient_dimension(),
                "metric of problem '" << inner.name() << "' has " << weights_.size()
                                      << " weights for n = " << inner.ambient_dimension());
  for (int i = 0; i < weights_.size(); ++i) {
    TESSERA_CHECK(std::isfinite(weights_(i)) && weights_(i) > 0,
                  "metric of problem '" << inner.name() << "': weight " << weights_(i)
                                        << " of coordinate " << i
                                        << " must be a finite number > 0");
  }
}

void ScaledProblem::evaluate(const Eigen::Ref<const Eigen::VectorXd>& y,
                             Eigen::Ref<Eigen::VectorXd> F) const {
  // Scratch kept between calls: correctors evaluate F millions of times.
  thread_local Eigen::VectorXd x;
  x = y.cwiseQuotient(weights_);
  inner_.evaluate(x, F);
}

void ScaledProblem::jacobian(const Eigen::Ref<const Eigen::VectorXd>& y,
                             Eigen::Ref<Eigen::MatrixXd> J) const {
  thread_local Eigen::VectorXd x;
  x = y.cwiseQuotient(weights_);
  inner_.jacobian(x, J);
  J = J * weights_.cwiseInverse().asDiagonal();
}

void ScaledProblem::sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& y,
                                    Eigen::SparseMatrix<double>& J) const {
  thread_local Eigen::VectorXd x;
  x = y.cwiseQuotient(weights_);
  inner_.sparse_jacobian(x, J);
  // Column j of DF scaled by 1/w_j, in place (the storage and pattern stay the problem's).
  J.makeCompressed();
  for (int j = 0; j < J.outerSize(); ++j) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(J, j); it; ++it) {
      it.valueRef() /= weights_(j);
    }
  }
}

std::vector<CoordinateBlock> ScaledProblem::coordinate_blocks() const {
  std::vector<CoordinateBlock> blocks = inner_.coordinate_blocks();
  for (CoordinateBlock& block : blocks) {
    block.weight = 1.0;
  }
  return blocks;
}

Domain scale_domain(const Domain& domain, const Eigen::VectorXd& weights) {
  if (domain.is_unbounded()) {
    return domain;
  }
  TESSERA_CHECK(weights.size() == domain.ambient_dimension(),
                "metric has " << weights.size() << " weights, the domain is in R^"
                              << domain.ambient_dimension());
  Domain scaled(domain.ambient_dimension());
  for (const HalfSpace& half_space : domain.half_spaces()) {
    scaled.add_half_space(half_space.normal.cwiseQuotient(weights),
                          half_space.point.cwiseProduct(weights), half_space.label);
  }
  return scaled;
}

}  // namespace tessera
