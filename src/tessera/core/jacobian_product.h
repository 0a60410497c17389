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
  /// JV = DF(y)·V for V (local rows × k) into JV (local equations × k, resized), and this
  /// rank's part of ‖DF(y)‖_F² (the caller sums the parts over the ranks, in rank order, so that
  /// every rank has the same bits). A collective call. Non-finite entries are passed on.
  virtual void jacobian_product(const Eigen::Ref<const Eigen::VectorXd>& y,
                                const Eigen::Ref<const Eigen::MatrixXd>& V, Eigen::MatrixXd& JV,
                                double& squared_frobenius_part) const = 0;
};

}  // namespace tessera
