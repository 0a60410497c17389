// SPDX-License-Identifier: MIT
#include "tessera/core/metric_problem.h"

namespace tessera {

MetricProblem::MetricProblem(const ImplicitProblem& problem) : weights_(metric_weights(problem)) {
  if (weights_.size() > 0) {
    scaled_ = std::make_unique<ScaledProblem>(problem, weights_);
  }
  counted_ = std::make_unique<CountedProblem>(scaled_ ? *scaled_ : problem);
}

Eigen::VectorXd MetricProblem::to_metric(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  return weights_.size() > 0 ? Eigen::VectorXd(weights_.cwiseProduct(x)) : Eigen::VectorXd(x);
}

Eigen::VectorXd MetricProblem::from_metric(const Eigen::Ref<const Eigen::VectorXd>& y) const {
  return weights_.size() > 0 ? Eigen::VectorXd(y.cwiseQuotient(weights_)) : Eigen::VectorXd(y);
}

double MetricProblem::length(const Eigen::Ref<const Eigen::VectorXd>& d) const {
  return weights_.size() > 0 ? weights_.cwiseProduct(d).norm() : d.norm();
}

WorkCounts MetricProblem::work() const {
  return {counted_->function_evaluations(), counted_->jacobian_evaluations(),
          counted_->factorisations()};
}

}  // namespace tessera
