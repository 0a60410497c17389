// SPDX-License-Identifier: MIT
// A problem seen in the coordinates of its metric, y = W x: Euclidean lengths in y are the
// problem's weighted lengths in x (see CoordinateBlock). Lets every method measure M in the
// metric without knowing about it.
#pragma once

#include <Eigen/Core>
#include <Eigen/SparseCore>
#include <memory>

#include "tessera/core/domain.h"
#include "tessera/core/implicit_problem.h"

namespace tessera {

/// F̃(y) = F(W⁻¹ y) with W = diag(weights), so DF̃(y) = DF(x) W⁻¹ and M̃ = W M.
///
/// A covering of M̃ in the Euclidean norm is a covering of M in the norm ‖x‖_W = ‖W x‖: steps,
/// radii, tolerances and distances all become lengths in the problem's metric. The inner
/// problem must outlive this one.
class ScaledProblem final : public ImplicitProblem {
 public:
  /// \param weights n positive finite weights (metric_weights(inner), when not empty).
  /// \throw InvalidArgument if weights has the wrong size or a weight is not finite and > 0.
  ScaledProblem(const ImplicitProblem& inner, Eigen::VectorXd weights);

  int ambient_dimension() const override { return inner_.ambient_dimension(); }
  void evaluate(const Eigen::Ref<const Eigen::VectorXd>& y,
                Eigen::Ref<Eigen::VectorXd> F) const override;
  void jacobian(const Eigen::Ref<const Eigen::VectorXd>& y,
                Eigen::Ref<Eigen::MatrixXd> J) const override;
  bool has_sparse_jacobian() const override { return inner_.has_sparse_jacobian(); }
  void sparse_jacobian(const Eigen::Ref<const Eigen::VectorXd>& y,
                       Eigen::SparseMatrix<double>& J) const override;
  std::string name() const override { return inner_.name(); }
  bool is_thread_safe() const override { return inner_.is_thread_safe(); }
  std::vector<std::string> coordinate_names() const override { return inner_.coordinate_names(); }
  /// The inner blocks with weight 1: in y the metric is already Euclidean.
  std::vector<CoordinateBlock> coordinate_blocks() const override;
  /// The inner problem's own factorisation (a distributed one), wrapped to factor DF̃ = DF W⁻¹;
  /// null (tessera's sparse or dense backend on DF̃) when the inner problem has none.
  std::unique_ptr<LinearizationBackend> make_linearization_backend() const override;

  const Eigen::VectorXd& weights() const { return weights_; }
  /// y = W x and x = W⁻¹ y.
  Eigen::VectorXd to_scaled(const Eigen::Ref<const Eigen::VectorXd>& x) const {
    return weights_.cwiseProduct(x);
  }
  Eigen::VectorXd from_scaled(const Eigen::Ref<const Eigen::VectorXd>& y) const {
    return y.cwiseQuotient(weights_);
  }

 private:
  const ImplicitProblem& inner_;
  Eigen::VectorXd weights_;
};

/// The domain W S in y = W x: {x : b·(x − p) ≥ 0} becomes {y : (W⁻¹b)·(y − W p) ≥ 0}.
/// \pre weights.size() == domain.ambient_dimension() (or the domain is unbounded): for a
/// distributed domain, this rank's rows of the weights (Domain::scaled; collective).
Domain scale_domain(const Domain& domain, const Eigen::VectorXd& weights);

}  // namespace tessera
