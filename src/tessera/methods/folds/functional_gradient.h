// SPDX-License-Identifier: MIT
// Gradients of view functionals (problems/view.h) for the curves computed on M: the fold curves
// over a parameter plane and the level curves of one functional.
#pragma once

#include <Eigen/Core>

#include "tessera/problems/view.h"

namespace tessera {

/// True for the functionals with a gradient wherever they are used: coordinates, mean:B, norm:B,
/// norm and expressions. False for max:B, min:B and absmax:B, which are not differentiable where
/// the extremum changes place.
bool is_differentiable(ViewFunctionalKind kind);

/// True for the functionals that are linear in x (coordinates and means): D²f = 0.
bool is_linear(ViewFunctionalKind kind);

/// "coordinates, mean:B, norm:B, norm or an expression": the differentiable functionals, for
/// error messages.
const char* differentiable_functionals();

/// For max:B, min:B and absmax:B: the coordinate (index into x) where the extremum of the block is
/// attained at x, the first on ties; NaN entries are passed over (−1 if all are NaN).
/// \throw InvalidArgument for another kind of functional.
int extremal_coordinate(const ViewFunctional& f, const Eigen::Ref<const Eigen::VectorXd>& x);

/// The gradient of f at x with respect to x (an n-vector).
///
/// Differentiable functionals: ∇f(x) (norm:B and norm, which have no gradient at 0, get 0
/// there). max:B, min:B and absmax:B: the gradient of the coordinate `active` that attains the
/// extremum (e_i, or sign(x_i)·e_i for absmax), which is ∇f wherever the extremum is attained
/// there only; `active` must then be a coordinate of the block.
///
/// \param metric_weights  the problem's metric_weights (n entries, for `norm`).
/// \param gradient  n entries, overwritten.
/// \throw InvalidArgument if sizes disagree or `active` is not in the block of an extremum.
void functional_gradient(const ViewFunctional& f,
                         const Eigen::Ref<const Eigen::VectorXd>& metric_weights,
                         const Eigen::Ref<const Eigen::VectorXd>& x,
                         Eigen::Ref<Eigen::VectorXd> gradient, int active = -1);

}  // namespace tessera
