// SPDX-License-Identifier: MIT
#include "tessera/methods/folds/functional_gradient.h"

#include <cmath>

#include "tessera/core/error.h"

namespace tessera {

bool is_differentiable(ViewFunctionalKind kind) {
  return kind != ViewFunctionalKind::BlockMaximum && kind != ViewFunctionalKind::BlockMinimum &&
         kind != ViewFunctionalKind::BlockAbsMaximum;
}

bool is_linear(ViewFunctionalKind kind) {
  return kind == ViewFunctionalKind::Coordinate || kind == ViewFunctionalKind::BlockMean;
}

const char* differentiable_functionals() {
  return "coordinates, mean:B, norm:B, norm or an expression";
}

int extremal_coordinate(const ViewFunctional& f, const Eigen::Ref<const Eigen::VectorXd>& x) {
  TESSERA_CHECK(!is_differentiable(f.kind),
                "extremal_coordinate: '" << f.label << "' is not a maximum or minimum of a block");
  TESSERA_CHECK(f.first >= 0 && f.first + f.size <= x.size(),
                "extremal_coordinate: '" << f.label << "' takes coordinates " << f.first << " … "
                                         << f.first + f.size - 1 << ", x has " << x.size());
  int best = -1;
  double best_value = 0.0;
  for (int i = f.first; i < f.first + f.size; ++i) {
    const double value = f.kind == ViewFunctionalKind::BlockMinimum      ? -x(i)
                         : f.kind == ViewFunctionalKind::BlockAbsMaximum ? std::abs(x(i))
                                                                         : x(i);
    if (!std::isnan(value) && (best < 0 || value > best_value)) {
      best = i;
      best_value = value;
    }
  }
  return best;
}

void functional_gradient(const ViewFunctional& f,
                         const Eigen::Ref<const Eigen::VectorXd>& metric_weights,
                         const Eigen::Ref<const Eigen::VectorXd>& x,
                         Eigen::Ref<Eigen::VectorXd> gradient, int active) {
  const Eigen::Index n = x.size();
  TESSERA_CHECK(gradient.size() == n && metric_weights.size() == n,
                "functional_gradient: x has " << n << " entries, the gradient " << gradient.size()
                                              << ", the metric weights " << metric_weights.size());
  gradient.setZero();
  switch (f.kind) {
    case ViewFunctionalKind::Coordinate:
      gradient(f.first) = 1.0;
      break;
    case ViewFunctionalKind::BlockMean:
      gradient.segment(f.first, f.size).setConstant(1.0 / f.size);
      break;
    case ViewFunctionalKind::BlockNorm: {
      // d/dx (w‖x_B‖) = w x_B / ‖x_B‖; at x_B = 0 the norm has no gradient: take 0 there.
      const double norm = x.segment(f.first, f.size).norm();
      if (norm > 0.0) {
        gradient.segment(f.first, f.size) = (f.weight / norm) * x.segment(f.first, f.size);
      }
      break;
    }
    case ViewFunctionalKind::Norm: {
      const double norm = metric_weights.cwiseProduct(x).norm();
      if (norm > 0.0) {
        gradient = metric_weights.cwiseAbs2().cwiseProduct(x) / norm;
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
        gradient(f.variables[k]) += partials(static_cast<Eigen::Index>(k));
      }
      break;
    }
    case ViewFunctionalKind::BlockMaximum:
    case ViewFunctionalKind::BlockMinimum:
    case ViewFunctionalKind::BlockAbsMaximum: {
      TESSERA_CHECK(active >= f.first && active < f.first + f.size,
                    "functional_gradient: '" << f.label
                                             << "' has no gradient where its extremum "
                                                "changes place; coordinate "
                                             << active << " is not one of its block (" << f.first
                                             << " … " << f.first + f.size - 1 << ")");
      // max and min: x_i itself; absmax: |x_i|.
      gradient(active) =
          f.kind == ViewFunctionalKind::BlockAbsMaximum && x(active) < 0.0 ? -1.0 : 1.0;
      break;
    }
  }
}

}  // namespace tessera
