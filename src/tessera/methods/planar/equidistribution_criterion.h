// SPDX-License-Identifier: MIT
// Approximate equidistribution (EQUID, Sweby; Malcolm section 4(9)): an edge costs the
// integral along it of the directional second derivative to the power 3/2.
#pragma once

#include <Eigen/Core>
#include <functional>

#include "tessera/methods/planar/swap_criterion.h"

namespace tessera {

/// Hessian of f at (x, y): [[f_xx, f_xy], [f_xy, f_yy]].
using HessianFunction = std::function<Eigen::Matrix2d(double x, double y)>;

/// EQUID: the cost of the edge v_a → v_b is ∫ w ds along it, w = |eᵀ H e|^{3/2} with e the
/// unit direction of the edge and H the Hessian of the function (the monitor function that
/// minimises the L2 error of linear interpolation, Carey and Dinh). The integral uses
/// Gauss–Legendre quadrature with 4 points (the report used Gaussian quadrature without saying
/// how many points). The absolute value is an addition: the report's (·)^{3/2} is undefined
/// where the directional second derivative is negative.
///
/// The cost depends on the edge alone, so the local and global tests differ only in which
/// costs are summed; the data values of the triangulation are not used.
class EquidistributionCriterion final : public SwapCriterion {
 public:
  /// \param hessian exact second derivatives of the function the data were sampled from.
  explicit EquidistributionCriterion(HessianFunction hessian);
  std::string name() const override { return "equid"; }
  Kind kind() const override { return Kind::EdgeCost; }
  double edge_cost(const PlanarTriangulation& triangulation, const EdgeQuadrilateral& q,
                   CostOrdering norm) const override;

 private:
  HessianFunction hessian_;
};

}  // namespace tessera
