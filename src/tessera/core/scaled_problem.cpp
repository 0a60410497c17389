// SPDX-License-Identifier: MIT
#include "tessera/core/scaled_problem.h"

#include <cmath>
#include <memory>
#include <utility>

#include "tessera/core/ambient_space.h"
#include "tessera/core/bordered_jacobian.h"
#include "tessera/core/error.h"
#include "tessera/core/linearization_backend.h"

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

namespace {

// The factorisation of DF̃(y) = DF(W⁻¹y) W⁻¹ from one of DF at x = W⁻¹y. ker DF̃ = W ker DF,
// orthonormalised in y. A solution dx of DF dx = r gives DF̃ (W dx) = r; removing its component
// in ker DF̃ leaves the minimum-norm one.
class ScaledBackend final : public LinearizationBackend {
 public:
  ScaledBackend(const ImplicitProblem& inner, const Eigen::VectorXd& weights,
                std::unique_ptr<LinearizationBackend> backend)
      : inner_(inner), weights_(weights), backend_(std::move(backend)) {}

  std::unique_ptr<LinearizationBackend> clone() const override {
    auto copy = std::make_unique<ScaledBackend>(inner_, weights_, backend_->clone());
    copy->inner_tangent_ = inner_tangent_;
    copy->last_tangent_ = last_tangent_;
    return copy;
  }
  bool clones_factorisation() const override { return backend_->clones_factorisation(); }

  bool factor(const ImplicitProblem& /*scaled*/, const Eigen::Ref<const Eigen::VectorXd>& y,
              const Eigen::MatrixXd* reference, Eigen::MatrixXd& tangent,
              double& reciprocal_condition) override {
    const Eigen::VectorXd x = y.cwiseQuotient(weights_);
    Eigen::MatrixXd guide;  // W⁻¹ T̃ spans ker DF when T̃ spans ker DF̃: it guides the border
    if (reference != nullptr) {
      guide = weights_.cwiseInverse().asDiagonal() * (*reference);
    }
    const long factorisations_before = backend_->factorisations();
    const long jacobians_before = backend_->own_jacobian_evaluations();
    const bool is_factored = backend_->factor(inner_, x, reference != nullptr ? &guide : nullptr,
                                              inner_tangent_, reciprocal_condition);
    factorisations_ += backend_->factorisations() - factorisations_before;
    own_jacobian_evaluations_ += backend_->own_jacobian_evaluations() - jacobians_before;
    if (!is_factored) {
      return false;
    }
    // W T spans ker DF̃; its basis is the one tessera's sparse backend would give on DF̃.
    tangent = weights_.asDiagonal() * inner_tangent_;
    return coordinate_tangent_basis(tangent, reference, last_tangent_);
  }

  void solve(const Eigen::Ref<const Eigen::VectorXd>& rhs, const Eigen::MatrixXd& tangent,
             Eigen::Ref<Eigen::VectorXd> dy) const override {
    solve_columns(rhs, tangent, dy);
  }

  void solve_columns(const Eigen::Ref<const Eigen::MatrixXd>& rhs, const Eigen::MatrixXd& tangent,
                     Eigen::Ref<Eigen::MatrixXd> dy) const override {
    backend_->solve_columns(rhs, inner_tangent_, dy);
    dy = weights_.asDiagonal() * dy;
    dy -= tangent * (tangent.transpose() * dy);
  }

  std::size_t memory_bytes() const override { return backend_->memory_bytes(); }
  void release_assembly() override { backend_->release_assembly(); }

 private:
  const ImplicitProblem& inner_;
  const Eigen::VectorXd& weights_;  // the ScaledProblem's, which outlives its linearisations
  std::unique_ptr<LinearizationBackend> backend_;
  Eigen::MatrixXd inner_tangent_;  // the inner backend's basis of ker DF
  Eigen::MatrixXd last_tangent_;   // guides the basis of the next factorisation, as in SparseBackend
};

}  // namespace

std::unique_ptr<LinearizationBackend> ScaledProblem::make_linearization_backend() const {
  std::unique_ptr<LinearizationBackend> inner = inner_.make_linearization_backend();
  if (!inner) {
    return nullptr;
  }
  return std::make_unique<ScaledBackend>(inner_, weights_, std::move(inner));
}

Domain scale_domain(const Domain& domain, const Eigen::VectorXd& weights) {
  if (domain.is_unbounded()) {
    return domain;
  }
  if (domain.is_distributed()) {
    return domain.scaled(weights);  // this rank's rows of the normals and weights
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
