// SPDX-License-Identifier: MIT
// DF(y)·V for problems whose Jacobian is not an Eigen matrix (the PETSc backend's distributed
// problem): what tangent_basis_near needs to find a tangent plane from a nearby factorisation.
#pragma once

#include <Eigen/Core>

namespace tessera {

/// Implemented, next to ImplicitProblem, by a problem whose `jacobian` and `sparse_jacobian` are
/// not available (petsc::DistributedProblem), which returns it from as_jacobian_product();
/// CountedProblem forwards it, counting each product as an evaluation of DF.
class JacobianProduct {
 public:
  virtual ~JacobianProduct() = default;
  /// Evaluates DF(y) (one evaluation of DF; a collective call) for the products below, and
  /// returns this rank's part of ‖DF(y)‖_F² (the caller sums the parts over the ranks, in rank
  /// order, so that every rank has the same bits). Non-finite entries are passed on.
  virtual double evaluate_jacobian_at(const Eigen::Ref<const Eigen::VectorXd>& y) const = 0;
  /// JV = DF(y)·V with DF(y) of the last evaluate_jacobian_at, for V (local rows × k) into JV
  /// (local equations × k, resized). A collective call.
  virtual void multiply_jacobian(const Eigen::Ref<const Eigen::MatrixXd>& V,
                                 Eigen::MatrixXd& JV) const = 0;
};

}  // namespace tessera
