// SPDX-License-Identifier: MIT
#include "tessera/methods/folds/parameter_plane.h"

#include <cmath>

#include "tessera/core/error.h"
#include "tessera/methods/folds/functional_gradient.h"

namespace tessera {

ParameterPlane::ParameterPlane(View view, Eigen::VectorXd metric_weights)
    : view_(std::move(view)), weights_(std::move(metric_weights)) {
  TESSERA_CHECK(view_.size() == 2, "a parameter plane needs two functionals, got "
                                       << view_.size() << " ('" << view_.specification()
                                       << "')");
  const int n = view_.ambient_dimension();
  if (weights_.size() == 0) {
    weights_ = Eigen::VectorXd::Ones(n);
  }
  TESSERA_CHECK(weights_.size() == n,
                "metric weights have " << weights_.size() << " entries, the view n = " << n);
  for (const ViewFunctional& functional : view_.functionals()) {
    TESSERA_CHECK(is_differentiable(functional.kind),
                  "'" << functional.label
                      << "' is not differentiable (the maximum or minimum of a block changes "
                         "place), so it cannot span a parameter plane; use "
                      << differentiable_functionals());
    is_linear_ = is_linear_ && tessera::is_linear(functional.kind);
  }
}

Eigen::Vector2d ParameterPlane::value(const Eigen::Ref<const Eigen::VectorXd>& x) const {
  ViewWorkspace workspace;
  Eigen::Vector2d values;
  view_.evaluate(x, values, workspace);
  return values;
}

void ParameterPlane::gradient(const Eigen::Ref<const Eigen::VectorXd>& x,
                              Eigen::Ref<Eigen::MatrixXd> G) const {
  const int n = ambient_dimension();
  TESSERA_CHECK(x.size() == n && G.rows() == 2 && G.cols() == n,
                "ParameterPlane::gradient: x has " << x.size() << " entries and G is " << G.rows()
                                                   << "×" << G.cols() << ", expected n = " << n);
  Eigen::VectorXd row(n);
  for (int i = 0; i < 2; ++i) {
    functional_gradient(view_.functionals()[static_cast<std::size_t>(i)], weights_, x, row);
    G.row(i) = row.transpose();
  }
}

ParameterPlane parse_parameter_plane(const std::string& specification,
                                     const ImplicitProblem& problem) {
  View view = parse_view(specification, problem);
  return ParameterPlane(std::move(view), metric_weights(problem));
}

}  // namespace tessera
