// SPDX-License-Identifier: MIT
// The parameter plane π: R^n → R² of a fold computation: two smooth functionals of x (usually
// the two parameters of a continuation problem), with their derivatives.
#pragma once

#include <Eigen/Core>
#include <string>

#include "tessera/problems/view.h"

namespace tessera {

/// π(x) = (p₁(x), p₂(x)) for two functionals of a View that are differentiable: coordinates,
/// mean:B, norm:B, norm and expressions (max:B, min:B and absmax:B are not differentiable where
/// the maximum changes place, so they cannot define a fold).
///
/// M folds over the plane where the restriction of Dπ to the tangent plane of M is singular.
class ParameterPlane {
 public:
  /// \param view  exactly two functionals (parse_view(spec, problem)).
  /// \param metric_weights  the problem's metric_weights (for `norm`); empty: all 1.
  /// \throw InvalidArgument if the view does not have two functionals or one is not
  ///        differentiable (the message names it and lists what can be used).
  ParameterPlane(View view, Eigen::VectorXd metric_weights = {});

  int ambient_dimension() const { return view_.ambient_dimension(); }
  const View& view() const { return view_; }
  /// "lambda, epsilon": the specification the plane was made from.
  std::string specification() const { return view_.specification(); }

  /// π(x). \pre x.size() == ambient_dimension().
  Eigen::Vector2d value(const Eigen::Ref<const Eigen::VectorXd>& x) const;
  /// G = Dπ(x), 2×n: row i is the gradient of functional i. \pre G is 2×n.
  void gradient(const Eigen::Ref<const Eigen::VectorXd>& x, Eigen::Ref<Eigen::MatrixXd> G) const;
  /// True if π is linear (coordinates and means only): then D²π = 0.
  bool is_linear() const { return is_linear_; }

 private:
  View view_;
  Eigen::VectorXd weights_;  // metric weights for `norm`, all 1 when the problem has none
  bool is_linear_ = true;
};

/// The parameter plane named by `specification` ("lambda,epsilon", or any two differentiable
/// view functionals) for `problem`.
/// \throw InvalidArgument naming the item for a bad specification, not two functionals, or a
///        functional that is not differentiable.
ParameterPlane parse_parameter_plane(const std::string& specification,
                                     const ImplicitProblem& problem);

}  // namespace tessera
