// SPDX-License-Identifier: MIT
#include "tessera/methods/folds/parameter_plane.h"

#include <cmath>

#include "tessera/core/error.h"

namespace tessera {

namespace {

bool is_differentiable(ViewFunctionalKind kind) {
  return kind != ViewFunctionalKind::BlockMaximum && kind != ViewFunctionalKind::BlockMinimum &&
         kind != ViewFunctionalKind::BlockAbsMaximum;
}

bool is_linear_kind(ViewFunctionalKind kind) {
  return kind == ViewFunctionalKind::Coordinate || kind == ViewFunctionalKind::BlockMean;
}

}  // namespace

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
                         "place), so it cannot span a parameter plane; use coordinates, mean:B, "
                         "norm:B, norm or an expression");
    is_linear_ = is_linear_ && is_linear_kind(functional.kind);
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
  G.setZero();
  for (int i = 0; i < 2; ++i) {
    const ViewFunctional& f = view_.functionals()[static_cast<std::size_t>(i)];
    auto row = G.row(i);
    switch (f.kind) {
      case ViewFunctionalKind::Coordinate:
        row(f.first) = 1.0;
        break;
      case ViewFunctionalKind::BlockMean:
        row.segment(f.first, f.size).setConstant(1.0 / f.size);
        break;
      case ViewFunctionalKind::BlockNorm: {
        // d/dx (w‖x_B‖) = w x_B / ‖x_B‖; at x_B = 0 the norm has no gradient: take 0 there.
        const double norm = x.segment(f.first, f.size).norm();
        if (norm > 0.0) {
          row.segment(f.first, f.size) = (f.weight / norm) * x.segment(f.first, f.size).transpose();
        }
        break;
      }
      case ViewFunctionalKind::Norm: {
        const double norm = weights_.cwiseProduct(x).norm();
        if (norm > 0.0) {
          row = (weights_.cwiseAbs2().cwiseProduct(x) / norm).transpose();
        }
        break;
      }
      case ViewFunctionalKind::Expression: {
        Eigen::VectorXd arguments(static_cast<Eigen::Index>(f.variables.size()));
        for (std::size_t k = 0; k < f.variables.size(); ++k) {
          arguments(static_cast<Eigen::Index>(k)) = x(f.variables[k]);
        }
        Eigen::VectorXd partials(arguments.size());
        ExpressionWorkspace workspace;
        f.expression->value_and_gradient(arguments, partials, workspace);
        for (std::size_t k = 0; k < f.variables.size(); ++k) {
          row(f.variables[k]) += partials(static_cast<Eigen::Index>(k));
        }
        break;
      }
      default:
        TESSERA_CHECK(false, "'" << f.label << "' is not differentiable");
    }
  }
}

ParameterPlane parse_parameter_plane(const std::string& specification,
                                     const ImplicitProblem& problem) {
  View view = parse_view(specification, problem);
  return ParameterPlane(std::move(view), metric_weights(problem));
}

}  // namespace tessera
